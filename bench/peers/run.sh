#!/bin/sh
# Peer benchmarks: mechgraph against the same calculations written in Python (numpy, scipy), each
# peer doing exactly mechgraph's work and checked to agree with it before it is timed (a peer that
# disagrees stops with exit status 1 and is reported FAILED). Each script times its sides in
# rounds (interleaved: one run of every side per round, the fastest run of each side counts), and
# each ratio is repeated in a summary at the end:
#   valvetrain_dynamics.py   valvetrain.dynamics (CVODE, dopri5) against scipy DOP853, RK45, Radau
#                            at equal error
#   valvetrain_stages123.py  stages 1-3 of the three-cam study over Latin-hypercube designs,
#                            designs/s, against the numpy grid peer and the closed-form peer
#   backlash_chain_mc.py     the Monte Carlo of backlash.chain, samples/s, against numpy with the
#                            same model (one normal per term, SFC64, blocks of 65,536)
# docs/peers.md says what each peer does and why it is fair. Builds nothing: uses $MECHGRAPH,
# else build/bin/mechgraph of this checkout, and Debian's /usr/bin/python3 (or $PYTHON) with
# python3-numpy and python3-scipy.
#
# Options: --quick (every peer: fewer tolerances, cases, samples and rounds), --repeats N (every
# peer), --only dynamics|stages123|mc (one peer); anything else goes to the dynamics peer (e.g.
# --all-methods for scipy's BDF and LSODA as well, --max-step for Radau with mechgraph's step cap).
set -u
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
mechgraph=${MECHGRAPH:-$root/build/bin/mechgraph}
python=${PYTHON:-/usr/bin/python3}
if [ ! -x "$mechgraph" ]; then
  echo "run.sh: no mechgraph at $mechgraph (build it, or set MECHGRAPH)" >&2
  exit 2
fi
if ! "$python" -c 'import numpy, scipy' 2>/dev/null; then
  echo "run.sh: $python lacks numpy/scipy (apt-get install -y python3-numpy python3-scipy)" >&2
  exit 2
fi

# Sort the arguments: the common ones are remembered, the rest stay in "$@" for the dynamics peer.
common=""
only=""
n=$#
while [ "$n" -gt 0 ]; do
  arg=$1
  shift
  n=$((n - 1))
  case $arg in
    --quick) common="$common --quick" ;;
    --repeats | --only)
      if [ "$n" -eq 0 ]; then
        echo "run.sh: $arg needs a value" >&2
        exit 2
      fi
      value=$1
      shift
      n=$((n - 1))
      if [ "$arg" = --only ]; then only=$value; else common="$common --repeats $value"; fi
      ;;
    --repeats=*) common="$common --repeats ${arg#--repeats=}" ;;
    --only=*) only=${arg#--only=} ;;
    *) set -- "$@" "$arg" ;;
  esac
done
case $only in
  "" | dynamics | stages123 | mc) ;;
  *)
    echo "run.sh: --only takes dynamics, stages123 or mc, not '$only'" >&2
    exit 2
    ;;
esac

log=$(mktemp "${TMPDIR:-/tmp}/mechgraph_peers.XXXXXX")
trap 'rm -f "$log" "$log.one" "$log.rc"' EXIT
trap 'exit 130' INT TERM
status=0

# run NAME SCRIPT ARGS...: the peer's output as it comes; its "ratio ..." lines kept for the summary.
run() {
  name=$1
  shift
  if [ -n "$only" ] && [ "$only" != "$name" ]; then return 0; fi
  echo "=== $name: $*" | sed "s|$root/||g"
  # One core for the peers as for mechgraph (OpenBLAS would thread numpy's matrix products), and
  # OpenBLAS left to detect this CPU itself.
  { env -u OPENBLAS_CORETYPE -u OPENBLAS_L2_SIZE OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 \
      "$python" -u "$@" 2>&1; echo $? >"$log.rc"; } | tee "$log.one"
  rc=$(cat "$log.rc")
  if [ "$rc" -eq 0 ]; then
    grep '^ratio' "$log.one" | sed "s|^|$name: |" >>"$log"
  else
    echo "$name: FAILED (exit status $rc)" >>"$log"
    status=1
  fi
  echo
}

# $common is a list of plain words (--quick, --repeats N): split on purpose.
# shellcheck disable=SC2086
run dynamics "$here/valvetrain_dynamics.py" --mechgraph "$mechgraph" --scene "$here/valvetrain_dynamics.yaml" $common "$@"
# shellcheck disable=SC2086
run stages123 "$here/valvetrain_stages123.py" --mechgraph "$mechgraph" --scene "$here/stages123_study.yaml" $common
# shellcheck disable=SC2086
run mc "$here/backlash_chain_mc.py" --mechgraph "$mechgraph" --scene "$root/scenes/backlash_chain.yaml" $common

echo "=== summary (mechgraph / Python peer; > 1: mechgraph faster)"
cat "$log"
exit $status
