# tests/untracked.sh — sourced by tests/run.sh and tests/fuzz/run.sh (POSIX
# sh, from the repository root): a test or fuzz run must leave the checkout
# as it found it. A fuzz run once wrote files named nan, rk4, 42 … into the
# root and they were committed by accident. Each run lists what git does not
# track (ignored files included, an untracked folder as one entry) at its
# start and again at its end; anything new outside the build folders fails.
# Outside a git checkout (an unpacked release) there is nothing to compare.

# What is untracked now, outside build/, build-san/ and $BUILD/, sorted.
untracked_now() {
    git rev-parse --is-inside-work-tree >/dev/null 2>&1 || return 0
    git ls-files --others --directory 2>/dev/null | while IFS= read -r p; do
        case "$p" in
        build/* | build-san/* | "${BUILD:-build}"/*) ;;
        *) printf '%s\n' "$p" ;;
        esac
    done | LC_ALL=C sort
}

# untracked_new BEFORE — what is untracked now and was not in the file
# BEFORE (untracked_now's list from the run's start).
untracked_new() {
    untracked_now | LC_ALL=C comm -13 "$1" -
}
