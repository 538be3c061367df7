# tribos_add_test(NAME <package.Class.behaviour>
#                 [SOURCES files... | EXE existing-target | COMMAND cmd args...]
#                 [ARGS args...] [LIBS libs...] [NP ranks] [THREADS n] [LABELS ...] [TIMEOUT s])
#
# SOURCES builds a GoogleTest executable linked with tribos_test_main (MPI + Kokkos set up
# once, output from rank 0 only, failure on any rank fails all); EXE reuses one already
# built, so one executable can run under 1, 2 and 4 ranks. NP runs it under mpirun with
# the flags that work as root (TOOLCHAIN.md); THREADS sets OMP_NUM_THREADS (default 1).
# Test names follow <package>.<Class>.<behaviour>[_np<N>] (STYLE.md 6).
include_guard(GLOBAL)

# Sanitizer run-time options (TRIBOS_SANITIZE=ON): stop at the first report, with stacks;
# child processes (tribos run by a driver test, ranks under mpirun) inherit the variables.
# Leak detection is off: Open MPI, Trilinos (Belos, Thyra, Tpetra registries) and Kokkos keep
# allocations for the life of the process, and their stacks through these uninstrumented
# libraries and Open MPI's unloaded plugins are too broken to suppress by library (measured:
# 69 of 79 tests failed on leaks, none with a frame in Tribos). The fuzz leg checks leaks of
# the readers, which run there without MPI or Trilinos (scripts/fuzz.sh).
set(TRIBOS_SANITIZER_ENVIRONMENT
  "ASAN_OPTIONS=halt_on_error=1:detect_leaks=0"
  "UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1:suppressions=${PROJECT_SOURCE_DIR}/test/sanitizer/ubsan.supp")

function(tribos_add_test)
  cmake_parse_arguments(T "" "NAME;NP;THREADS;TIMEOUT;EXE" "SOURCES;COMMAND;ARGS;LIBS;LABELS" ${ARGN})
  if(NOT T_THREADS)
    set(T_THREADS 1)
  endif()
  if(T_SOURCES)
    string(REPLACE "." "_" exe "test_${T_NAME}")
    add_executable(${exe} ${T_SOURCES})
    target_link_libraries(${exe} PRIVATE tribos_test_main ${T_LIBS})
    # The sanitizer leg (scripts/sanitize.sh): a test's own file at -O0, compiled in about half
    # the time of -O1 (gtest's macros and the test's templates are most of it); the code it
    # tests, in the libraries, stays at the leg's -O1, where the tests spend their time.
    if(TRIBOS_SANITIZE)
      target_compile_options(${exe} PRIVATE -O0)
    endif()
    set(cmd $<TARGET_FILE:${exe}> ${T_ARGS})
  elseif(T_EXE)
    set(cmd $<TARGET_FILE:${T_EXE}> ${T_ARGS})
  else()
    set(cmd ${T_COMMAND} ${T_ARGS})
  endif()
  # The processors a test occupies: ranks x threads (a 2-thread test without MPI takes 2, so
  # ctest -j2 does not run a second test beside it).
  set(procs ${T_THREADS})
  if(T_NP)
    # OMP_WAIT_POLICY=PASSIVE: idle OpenMP threads sleep instead of spinning, which matters
    # when ranks x threads exceed the cores (CI has 2): spinning threads starve the ranks.
    set(cmd ${MPIEXEC_EXECUTABLE} --allow-run-as-root --oversubscribe --bind-to none
            -x OMP_NUM_THREADS=${T_THREADS} -x OMP_WAIT_POLICY=PASSIVE ${MPIEXEC_NUMPROC_FLAG} ${T_NP} ${cmd})
    math(EXPR procs "${T_NP} * ${T_THREADS}")
  endif()
  add_test(NAME ${T_NAME} COMMAND ${cmd})
  if(NOT T_TIMEOUT)
    set(T_TIMEOUT 300)
  endif()
  set(environment OMP_NUM_THREADS=${T_THREADS} OMP_WAIT_POLICY=PASSIVE OMPI_ALLOW_RUN_AS_ROOT=1
      OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1 TRIBOS_SOURCE_DIR=${PROJECT_SOURCE_DIR})
  if(TRIBOS_SANITIZE)
    list(APPEND environment ${TRIBOS_SANITIZER_ENVIRONMENT})
  endif()
  set_tests_properties(${T_NAME} PROPERTIES
    LABELS "${T_LABELS}" TIMEOUT ${T_TIMEOUT} PROCESSORS ${procs} ENVIRONMENT "${environment}")
endfunction()
