#pragma once
/// \file InputFiles.hpp
/// The files a run reads (the scene, its mesh): only regular files, so that a FIFO, a device
/// or a directory given by mistake is an input error at once and never a hang or a read that
/// does not end (`--input /dev/zero`).
#include <cstdint>
#include <string>

namespace tribos::core {

/// Throws InputError naming `path` and `what` (e.g. "the scene file", "Mesh/File") unless
/// `path` names an existing regular file (symbolic links followed). Never opens the file, so
/// it cannot block on a FIFO.
void requireRegularInputFile(const std::string& path, const std::string& what);

/// The whole of the regular file `path`, read only if it holds at most `maxBytes` bytes (and
/// stopped there should it grow while it is read). Throws InputError naming `path`, `what`
/// and the cap otherwise, or when it cannot be read.
std::string readRegularTextFile(const std::string& path, const std::string& what, std::uintmax_t maxBytes);

/// True when `a` and `b` name the same file: the same device and inode when both exist
/// (hard and symbolic links, "./x" and "x"), else the same absolute path with ".", ".." and
/// the links of its existing part resolved.
bool sameFile(const std::string& a, const std::string& b);

}  // namespace tribos::core
