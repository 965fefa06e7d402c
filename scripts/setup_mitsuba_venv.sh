#!/usr/bin/env bash
# The peer for bench/bench_vs_mitsuba.py: Mitsuba 3 from PyPI, pinned, with numpy, the OpenEXR
# Python module and pillow (bench/side_by_side.py runs in it too), in a venv of Debian's python3 at /opt/mitsuba (PT_MITSUBA_VENV overrides), and
# libllvm19 from Debian 12 (Dr.Jit's LLVM back end needs LLVM >= 16 for fminimum/fmaximum; Mesa's
# LLVM 15 is not enough). Not part of scripts/setup.sh: only this benchmark needs it.
# Idempotent and quiet when done.
set -euo pipefail
if [ "$(id -u)" -ne 0 ]; then SUDO=sudo; else SUDO=; fi
venv=${PT_MITSUBA_VENV:-/opt/mitsuba}
mitsuba_version=3.9.1
if [ ! -e /usr/lib/x86_64-linux-gnu/libLLVM.so.19.1 ] && ! dpkg-query -W -f='${Status}' libllvm19 2>/dev/null | grep -q "install ok installed"; then
  echo "setup: installing libllvm19"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends libllvm19 >/dev/null
fi
if "$venv/bin/python" -c "import mitsuba, numpy, OpenEXR, PIL, sys; sys.exit(mitsuba.__version__ != '$mitsuba_version')" 2>/dev/null; then
  exit 0
fi
echo "setup: installing mitsuba==$mitsuba_version numpy OpenEXR pillow into $venv"
$SUDO /usr/bin/python3 -m venv "$venv"
$SUDO "$venv/bin/pip" install -q --disable-pip-version-check "mitsuba==$mitsuba_version" numpy OpenEXR pillow
