#!/bin/sh
# Peer benchmark of valvetrain.dynamics against scipy (bench/peers/valvetrain_dynamics.py).
# Builds nothing: uses $MECHGRAPH, else build/bin/mechgraph of this checkout, and Debian's
# /usr/bin/python3 with python3-numpy and python3-scipy. Extra arguments go to the script
# (--repeats N, --quick, --all-methods for scipy's BDF and LSODA as well).
set -eu
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
exec "$python" "$here/valvetrain_dynamics.py" --mechgraph "$mechgraph" --scene "$here/valvetrain_dynamics.yaml" "$@"
