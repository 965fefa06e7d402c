#!/usr/bin/env bash
# The Ray driver's Python environment (tools/pt_ray): Ray from PyPI, pinned, in a venv of
# Debian's python3 at /opt/pt-ray (PT_RAY_VENV overrides). Idempotent and quiet when done. If
# PyPI cannot be reached it says so and carries on: the Ray tests then skip themselves.
set -euo pipefail
if [ "$(id -u)" -ne 0 ]; then SUDO=sudo; else SUDO=; fi
venv=${PT_RAY_VENV:-/opt/pt-ray}
ray_version=2.60.0
if "$venv/bin/python" -c "import ray, sys; sys.exit(ray.__version__ != '$ray_version')" 2>/dev/null; then
  exit 0
fi
echo "setup: installing ray==$ray_version into $venv"
$SUDO /usr/bin/python3 -m venv "$venv"
$SUDO "$venv/bin/pip" install -q --disable-pip-version-check "ray==$ray_version" \
  || echo "setup: could not install ray from PyPI; the Ray driver's tests will be skipped"
