# Sourced by the scripts that run sanitized programs: the first report of
# AddressSanitizer (memory errors, leaks) or UndefinedBehaviorSanitizer ends the
# program with an error, with a stack trace.
ASAN_OPTIONS=${ASAN_OPTIONS:-halt_on_error=1:detect_leaks=1:check_initialization_order=1}
UBSAN_OPTIONS=${UBSAN_OPTIONS:-halt_on_error=1:print_stacktrace=1}
export ASAN_OPTIONS UBSAN_OPTIONS
