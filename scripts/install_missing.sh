#!/usr/bin/env bash
# Installs the named Debian packages that are not installed yet (apt-get, as root or through
# sudo); quiet and fast when all are there. Sourced by scripts/setup.sh and scripts/fuzz.sh.
# Usage: install_missing LABEL PACKAGE...
install_missing() {
  local label=$1 p
  shift
  local missing=()
  for p in "$@"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  ((${#missing[@]})) || return 0
  echo "$label: installing ${#missing[@]} missing Debian package(s): ${missing[*]}"
  local sudo_cmd=()
  [ "$(id -u)" -ne 0 ] && sudo_cmd=(sudo)
  export DEBIAN_FRONTEND=noninteractive
  "${sudo_cmd[@]}" apt-get update -qq
  "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
}
