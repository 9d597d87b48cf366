# Preamble shared by the work-precision scripts (work_precision_schemes.sh,
# adaptive_steps.sh, adaptive_mesh.sh, error_budget.sh). Source it after
# bench/quick_option.sh with the program to run, relative to the build directory:
#   . "$repo_root/bench/build_for_bench.sh" rodcontact
# It builds a Release build with scripts/setup.sh (its output on stderr) unless WP_SKIP_BUILD=1,
# and sets build_dir (BUILD_DIR, default build/, relative to the repository), exe (exits 1 when
# it is not built), out (WP_OUT; default out/bench, with --quick out/bench-quick) and ref_libs
# (the LD_LIBRARY_PATH of the reference BLAS/LAPACK that bench.sh measures with, if installed;
# else empty).
if [[ "${WP_SKIP_BUILD:-0}" != 1 ]]; then
    BUILD_TYPE=Release "$repo_root/scripts/setup.sh" >&2
fi
build_dir="${BUILD_DIR:-build}"
[[ "$build_dir" = /* ]] || build_dir="$repo_root/$build_dir"
exe="$build_dir/$1"
[[ -x "$exe" ]] || { say "$exe not built"; exit 1; }
if ((quick)); then out="${WP_OUT:-$repo_root/out/bench-quick}"; else out="${WP_OUT:-$repo_root/out/bench}"; fi
ref_libs="/usr/lib/x86_64-linux-gnu/blas:/usr/lib/x86_64-linux-gnu/lapack"
[[ -d /usr/lib/x86_64-linux-gnu/blas && -d /usr/lib/x86_64-linux-gnu/lapack ]] || ref_libs=""
