# Environment for running the test suite of a -DGRAINS_SANITIZE=ON build
# (docs/sanitizers.md):  source tests/sanitizers/env.sh; ctest --test-dir build-asan -LE long
_grains_san_dir=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
# Leaks are checked; Open MPI's own start-up allocations are suppressed by
# library (lsan.supp), never ours.
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=0:strict_string_checks=1:detect_stack_use_after_return=0
export LSAN_OPTIONS=suppressions=$_grains_san_dir/lsan.supp:print_suppressions=0
# Any undefined behaviour stops the program with a stack trace (the build
# also has -fno-sanitize-recover=undefined).
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
# Open MPI loads its MCA components with dlopen and closes them before exit;
# LSan then reports their start-up allocations from "<unknown module>", which
# no suppression by library name can match. Keeping them loaded lets
# lsan.supp name them (found by the first full run, 2026-11-21). The
# suppressions also need whole stacks: with ASan's fast unwinding a stack
# stops at the first frame without a frame pointer (inside Open MPI), so
# tests run under mpirun need ASAN_OPTIONS=...:fast_unwind_on_malloc=0
# (CMake appends it per test for the MPI tests, ENVIRONMENT_MODIFICATION in
# the sanitize build only: it slows every malloc).
export OMPI_MCA_mca_base_component_disable_dlclose=1
unset _grains_san_dir
