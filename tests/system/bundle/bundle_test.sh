#!/usr/bin/env bash
# The bundle (scripts/bundle.sh) runs a scene at 2 ranks from an empty folder with the system's
# libraries out of reach: the environment emptied (env -i) but for the bundle's bin/ on PATH, every
# library each process loads traced by the dynamic loader (LD_DEBUG=libs), and every one of them
# must come from the bundle but the C library and loader family (and the launchers' shell's own
# libtinfo); PETSc, SUNDIALS, HDF5, MPI, METIS and Open MPI's components are checked by name in both
# ranks. The bundle's output must be bitwise that of the build's raceway at 1 rank.
#   bundle_test.sh SOURCE_DIR BUILD_DIR RACEWAY
set -uo pipefail
case_name=bundle
source "$(dirname "${BASH_SOURCE[0]}")/../test_lib.sh"
src=${1:?source folder} build=${2:?build folder} raceway=${3:?raceway}
if ! command -v ompi_info >/dev/null || ! command -v orterun >/dev/null; then
  echo "SKIP: no Open MPI launcher (orterun, ompi_info): the bundle packs Open MPI's"
  exit 77
fi

start=$SECONDS
"$src/scripts/bundle.sh" --build "$build" --output "$work/raceway-bundle.tar.gz" --fast >"$work/bundle.log" 2>&1 ||
  { cat "$work/bundle.log"; fail "scripts/bundle.sh failed"; finish; }
echo "$(tail -1 "$work/bundle.log") in $((SECONDS - start)) s"
mkdir "$work/elsewhere"
cd "$work/elsewhere" || exit 1
tar xzf "$work/raceway-bundle.tar.gz" || { fail "the archive does not unpack"; finish; }
B=$work/elsewhere/raceway-bundle
[[ -z $(find "$B" -type l) ]] || fail "the bundle holds links: $(find "$B" -type l | head -3)"

# Statically: every library of raceway resolves inside the bundle (but the C library family).
core='/(ld-linux[^/]*|libc|libm|libmvec|libdl|libpthread|librt|libresolv|libutil|libanl|libnsl|libthread_db|libnss_[a-z0-9]+)\.so[^/]*$'
outside=$(LD_LIBRARY_PATH=$B/lib ldd "$B/libexec/raceway" | awk '/=>/ {print $3}' | grep -v "^$B/" | grep -Ev "$core")
[[ -z $outside ]] || fail "raceway's libraries outside the bundle: $outside"

# The run, from the empty folder, with nothing of the system on PATH or the library path.
cp "$src/jobs/scenes/6309_R3.toml" scene.toml
mkdir trace
env -i HOME="$work" PATH="$B/bin" LD_DEBUG=libs LD_DEBUG_OUTPUT="$work/elsewhere/trace/ld" \
  OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_btl_vader_single_copy_mechanism=none \
  OMPI_MCA_mpi_yield_when_idle=1 ./raceway-bundle/bin/mpirun -np 2 ./raceway-bundle/bin/raceway run scene.toml \
  --set scene.end_time=3ms -o bundled.h5 >run.log 2>&1
rc=$?
[[ $rc -eq 0 ]] || { tail -20 run.log; fail "the bundled run exited $rc"; }
grep -q 'done: ' run.log || fail "the bundled run did not finish (no 'done:' line)"
grep -q '2 ranks' run.log || fail "the bundled run did not run on 2 ranks: $(grep scheduler run.log | head -2)"

# Every object any process loaded (LD_DEBUG's "calling init: PATH").
loaded=$(grep -h 'calling init:' trace/ld.* | awk '{print $NF}' | sort -u)
[[ -n $loaded ]] || fail "no loader trace (LD_DEBUG) was written"
stray=$(grep -v "^$B/" <<<"$loaded" | grep -Ev "$core" | grep -Ev '/libtinfo\.so[^/]*$')
[[ -z $stray ]] || fail "loaded from outside the bundle: $(tr '\n' ' ' <<<"$stray")"
# By name, in each rank (the traces that loaded PETSc are the ranks'), from the bundle only.
rank_traces=$(grep -l 'calling init:.*libpetsc' trace/ld.* | wc -l)
[[ $rank_traces -eq 2 ]] || fail "$rank_traces processes loaded PETSc, expected the 2 ranks"
for lib in libpetsc libsundials_cvode libhdf5_openmpi libmpi.so libmetis libopen-pal openmpi/mca_btl_vader \
  openmpi/mca_pml_ob1 libpmix pmix/pmix_mca; do
  found=$(grep -h "calling init:.*$lib" trace/ld.* | awk '{print $NF}' | sort -u)
  [[ -n $found ]] || { fail "$lib was not loaded"; continue; }
  grep -qv "^$B/" <<<"$found" && fail "$lib loaded from outside the bundle: $found"
  [[ $lib == libpmix || $lib == pmix/* || $lib == libopen-pal ]] && continue  # the launcher's too
  n=$(grep -l "calling init: $B/lib/$lib" trace/ld.* | wc -l)
  [[ $n -ge 2 ]] || fail "$lib: loaded by $n process(es), expected both ranks"
done

# The same bits as the build's raceway at 1 rank.
"$raceway" run scene.toml --set scene.end_time=3ms -o built.h5 >built.log 2>&1 || fail "the build's raceway failed"
if /usr/bin/python3 -c 'import h5py, numpy' 2>/dev/null; then
  /usr/bin/python3 "$src/scripts/compare_outputs.py" built.h5 bundled.h5 >compare.log 2>&1 ||
    { cat compare.log; fail "the bundled run's output differs from the build's"; }
else
  echo "note: no h5py for /usr/bin/python3: outputs not compared"
fi
echo "bundle test: $((SECONDS - start)) s"
finish
