#!/usr/bin/env bash
# A relocatable bundle of raceway: the built executable, every shared library it and Open MPI need
# (found with ldd), Open MPI's launcher, components, help files and settings, PMIx's components, the
# measured tables of data/ and the report's Python, in one compressed archive that runs on another
# x86-64 Linux machine without installing anything (docs/install.md, "A bundle for a cluster").
#
#   scripts/bundle.sh [--build DIR] [--output FILE.tar.gz] [--fast]
#       --build   the configured and built tree (default: build)
#       --output  the archive (default: raceway-bundle.tar.gz); it unpacks into raceway-bundle/
#       --fast    gzip -1 instead of -6 (the tests: a larger archive, made in a third of the time)
#
# In the archive (raceway-bundle/):
#   bin/mpirun, bin/raceway, bin/orted   launchers: each sets the environment below from its own
#                                        folder and runs the real program in libexec/ (and
#                                        bin/pingpong, the MPI ping-pong, when perf/bench is built)
#   bin/raceway-env.sh                   the same environment for a shell: . raceway-bundle/bin/raceway-env.sh
#   libexec/                             raceway, Open MPI's orterun (mpirun) and orted, pingpong
#   lib/                                 the shared libraries (all but the C library and loader
#                                        family, which every Linux has and which must match its kernel)
#   lib/openmpi, share/openmpi, etc/openmpi   Open MPI's components, help texts, MCA settings
#   lib/pmix, share/pmix, etc/           PMIx's components and help texts
#   lib/ucx                              UCX's transport modules (when Open MPI's UCX component is there)
#   share/raceway/data, share/raceway/report, lib/python3*/   cmake --install's tree
# The environment: LD_LIBRARY_PATH (the bundle's lib/ first), OPAL_PREFIX and Open MPI's other
# installation-folder variables (OPAL_LIBDIR, OPAL_PKGLIBDIR, OPAL_PKGDATADIR, OPAL_SYSCONFDIR, ...),
# PMIx's (PMIX_PREFIX, PMIX_PKGLIBDIR, ...), HWLOC_PLUGINS_PATH, PATH (bin/ first).
#
# Needs: cmake (for cmake --install), ldd, Open MPI's orterun/orted (Debian's openmpi-bin), tar, gzip.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=build output=raceway-bundle.tar.gz level=6
while [[ $# -gt 0 ]]; do
  case $1 in
    --build) build=${2:?--build DIR}; shift 2 ;;
    --output) output=${2:?--output FILE}; shift 2 ;;
    --fast) level=1; shift ;;
    -h | --help) sed -n '2,30p' "${BASH_SOURCE[0]}"; exit 0 ;;
    *) echo "bundle: unknown argument $1 (see --help)" >&2; exit 2 ;;
  esac
done
die() { echo "bundle: $*" >&2; exit 1; }
cd "$root"
[[ -x $build/raceway ]] || die "$build/raceway: not built (cmake --build $build)"
orterun=$(command -v orterun || true)
[[ -n $orterun ]] || orterun=$(readlink -f "$(command -v mpirun || echo /nonexistent)" 2>/dev/null || true)
[[ -x $orterun ]] || die "no Open MPI launcher (orterun/mpirun; apt-get install openmpi-bin)"
orted=$(dirname "$orterun")/orted
[[ -x $orted ]] || die "no orted beside $orterun"
command -v ompi_info >/dev/null || die "no ompi_info (Open MPI's; apt-get install openmpi-bin)"
# Open MPI's installation folders, as it was built.
ompi_path() { ompi_info --path "$1" --parsable | sed -n "s/^path:$1://p"; }
ompi_libdir=$(ompi_path libdir) ompi_pkglibdir=$(ompi_path pkglibdir)
ompi_pkgdatadir=$(ompi_path pkgdatadir) ompi_sysconfdir=$(ompi_path sysconfdir)
[[ -d $ompi_pkglibdir ]] || die "Open MPI's component folder $ompi_pkglibdir is missing"

stage=$(mktemp -d "${TMPDIR:-/tmp}/raceway-bundle.XXXXXX")
trap 'rm -rf "$stage"' EXIT
B=$stage/raceway-bundle
cmake --install "$build" --prefix "$B" >"$stage/install.log" || die "cmake --install failed: $(tail -3 "$stage/install.log")"
mkdir -p "$B/libexec" "$B/lib/openmpi" "$B/share" "$B/etc"
mv "$B/bin/raceway" "$B/libexec/raceway"
cp -L "$orterun" "$B/libexec/orterun"
cp -L "$orted" "$B/libexec/orted"
# The MPI ping-pong benchmark, when built (perf/calibration/run_node_scaling.sh measures the network).
[[ -x $build/perf/bench/pingpong ]] && cp -L "$build/perf/bench/pingpong" "$B/libexec/pingpong"
cp -L "$ompi_pkglibdir"/*.so "$B/lib/openmpi/"
cp -rL "$ompi_pkgdatadir" "$B/share/openmpi"
cp -rL "$ompi_sysconfdir" "$B/etc/openmpi"
# Open MPI's own libraries beside its components (libmca_common_*, loaded by them).
cp -L "$ompi_libdir"/libmca_common_*.so* "$B/lib/" 2>/dev/null || true
# PMIx: its components and help texts (PMIX_PKGLIBDIR, PMIX_PKGDATADIR, PMIX_SYSCONFDIR).
pmix_lib=$(ldd "$ompi_pkglibdir"/mca_pmix_*.so 2>/dev/null | awk '/libpmix\.so/ {print $3; exit}')
if [[ -n $pmix_lib ]]; then
  pmix_prefix=$(dirname "$(dirname "$(readlink -f "$pmix_lib")")")
  [[ -d $pmix_prefix/lib/pmix ]] && cp -rL "$pmix_prefix/lib/pmix" "$B/lib/pmix"
  [[ -d $pmix_prefix/share/pmix ]] && cp -rL "$pmix_prefix/share/pmix" "$B/share/pmix"
  [[ -d $pmix_prefix/etc ]] && cp -rL "$pmix_prefix/etc/." "$B/etc/"
fi

# The C library and loader family: every Linux has it, and it must match the machine's kernel.
is_system_core() {
  [[ $(basename "$1") =~ ^(ld-linux.*|libc|libm|libmvec|libdl|libpthread|librt|libresolv|libutil|libanl|libnsl|libthread_db|libBrokenLocale|libc_malloc_debug|libnss_[a-z0-9]+)\.so ]]
}
# Every library the programs and components need, transitively (ldd resolves the whole tree).
objects=("$B"/libexec/* "$B"/lib/openmpi/*.so "$B"/lib/libmca_common_*.so*)
[[ -d $B/lib/pmix ]] && objects+=("$B"/lib/pmix/*.so)
copy_dependencies() {
  local path
  ldd "$@" 2>/dev/null | awk '/=> \// {print $3} /^\t\/[^ ]+ \(/ {print $1}' | sort -u | while read -r path; do
    is_system_core "$path" && continue
    [[ -e $B/lib/$(basename "$path") ]] || cp -L "$path" "$B/lib/"
  done
}
copy_dependencies "${objects[@]}"
# UCX loads its transports from ucx/ beside libucs.
if ucs=$(ls "$B"/lib/libucs.so.* 2>/dev/null | head -1) && [[ -n $ucs ]]; then
  ucs_dir=$(dirname "$(ldd "$B/lib/openmpi/"*ucx*.so 2>/dev/null | awk '/libucs\.so/ {print $3; exit}')")
  if [[ -d $ucs_dir/ucx ]]; then
    cp -rL "$ucs_dir/ucx" "$B/lib/ucx"
    copy_dependencies "$B"/lib/ucx/*.so*
  fi
fi

# hwloc's plugins (the machine's topology; loaded by Open MPI's hwloc).
hwloc_lib=$(ldd "$B/libexec/orterun" | awk '/libhwloc\.so/ {print $3; exit}')
if [[ -n $hwloc_lib && -d $(dirname "$hwloc_lib")/hwloc ]]; then
  cp -rL "$(dirname "$hwloc_lib")/hwloc" "$B/lib/hwloc"
  copy_dependencies "$B"/lib/hwloc/*.so
fi

# The launchers. Only shell built-ins find the bundle, so they run with PATH reaching nothing else.
cat >"$B/bin/raceway-env.sh" <<'ENV'
# The bundle's environment (sourced by bin/mpirun, bin/raceway, bin/orted, or by a shell:
# . raceway-bundle/bin/raceway-env.sh). RACEWAY_BUNDLE: the bundle's folder.
if [ -z "${RACEWAY_BUNDLE:-}" ]; then
  RACEWAY_BUNDLE=$(cd "$(dirname "${BASH_SOURCE[0]:-$0}")/.." && pwd -P)
fi
export RACEWAY_BUNDLE
export LD_LIBRARY_PATH="$RACEWAY_BUNDLE/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
export PATH="$RACEWAY_BUNDLE/bin${PATH:+:$PATH}"
# Open MPI finds its components, help texts and settings through these (opal installdirs env).
export OPAL_PREFIX="$RACEWAY_BUNDLE" OPAL_EXEC_PREFIX="$RACEWAY_BUNDLE" OPAL_BINDIR="$RACEWAY_BUNDLE/bin"
export OPAL_LIBDIR="$RACEWAY_BUNDLE/lib" OPAL_PKGLIBDIR="$RACEWAY_BUNDLE/lib/openmpi"
export OPAL_DATAROOTDIR="$RACEWAY_BUNDLE/share" OPAL_DATADIR="$RACEWAY_BUNDLE/share"
export OPAL_PKGDATADIR="$RACEWAY_BUNDLE/share/openmpi" OPAL_SYSCONFDIR="$RACEWAY_BUNDLE/etc/openmpi"
export OPAL_INCLUDEDIR="$RACEWAY_BUNDLE/include" OPAL_LIBEXECDIR="$RACEWAY_BUNDLE/libexec"
# PMIx (Open MPI's process management): its components, help texts and settings (pinstalldirs env).
export PMIX_PREFIX="$RACEWAY_BUNDLE" PMIX_EXEC_PREFIX="$RACEWAY_BUNDLE" PMIX_LIBDIR="$RACEWAY_BUNDLE/lib"
export PMIX_PKGLIBDIR="$RACEWAY_BUNDLE/lib/pmix" PMIX_DATADIR="$RACEWAY_BUNDLE/share"
export PMIX_PKGDATADIR="$RACEWAY_BUNDLE/share/pmix" PMIX_SYSCONFDIR="$RACEWAY_BUNDLE/etc"
# Nodes that are not this one start orted from here (a bundle on a shared file system).
export OMPI_MCA_orte_launch_agent="$RACEWAY_BUNDLE/bin/orted"
# Without ssh or rsh (a container), mpirun refuses to start even on one node: give it an agent that
# exists and is never called there.
if [ -z "${OMPI_MCA_plm_rsh_agent:-}" ] && ! command -v ssh >/dev/null 2>&1 && ! command -v rsh >/dev/null 2>&1; then
  export OMPI_MCA_plm_rsh_agent=/bin/false
fi
# hwloc (Open MPI's view of the cores) loads its plugins from here.
export HWLOC_PLUGINS_PATH="$RACEWAY_BUNDLE/lib/hwloc"
ENV
programs=(raceway orterun orted)
[[ -x $B/libexec/pingpong ]] && programs+=(pingpong)
for program in "${programs[@]}"; do
  launcher=$program
  [[ $program == orterun ]] && launcher=mpirun
  cat >"$B/bin/$launcher" <<LAUNCH
#!/bin/bash
# The bundle's $launcher: its environment, then libexec/$program.
here=\${BASH_SOURCE[0]%/*}
[[ \$here == "\${BASH_SOURCE[0]}" ]] && here=.
RACEWAY_BUNDLE=\$(cd "\$here/.." && pwd -P)
. "\$RACEWAY_BUNDLE/bin/raceway-env.sh"
exec "\$RACEWAY_BUNDLE/libexec/$program" "\$@"
LAUNCH
  chmod +x "$B/bin/$launcher"
done
cat >"$B/README.txt" <<'README'
raceway, with the shared libraries it needs (see docs/install.md of the sources, "A bundle for a cluster").

  tar xzf raceway-bundle.tar.gz
  raceway-bundle/bin/raceway --version
  raceway-bundle/bin/mpirun -np 4 raceway-bundle/bin/raceway run scene.toml -o out.h5
  . raceway-bundle/bin/raceway-env.sh    # or: the environment in this shell, then mpirun/raceway

bin/ holds launchers that set LD_LIBRARY_PATH and Open MPI's OPAL_* folders from where the bundle lies;
the C library is the machine's own (glibc 2.36 or newer needed, as built on Debian 12).
README
"$B/bin/raceway" --version >"$B/VERSION" || die "the bundled raceway does not start: $(cat "$B/VERSION")"
output_abs=$(cd "$(dirname "$output")" && pwd)/$(basename "$output")
tar -C "$stage" -cf - raceway-bundle | gzip "-$level" >"$output_abs.part"
mv "$output_abs.part" "$output_abs"
echo "bundle: $output_abs ($(du -h "$output_abs" | cut -f1), $(ls "$B/lib" | wc -l) libraries, $(head -1 "$B/VERSION"))"
