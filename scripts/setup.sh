#!/usr/bin/env bash
# Installs everything pt needs to build, render and test on Debian 12 (bookworm).
# Idempotent: packages already present are skipped and the script stays quiet.
# Lavapipe comes from bookworm-backports (Mesa 25), which runs our kernel about
# 3.5x faster than Debian 12's own Mesa 22 (see bench/RESULTS.md); the renderer
# still works on Mesa 22.
set -euo pipefail

if [ "$(id -u)" -ne 0 ]; then SUDO=sudo; else SUDO=; fi

here=$(dirname "$0")
# The packages: scripts/debian-packages.txt, one a line with what uses it after a `#`
# (tests/setup/setup_completeness_test.py checks that it covers everything the repository uses).
mapfile -t packages < <(sed -e 's/#.*//' -e 's/[[:space:]]//g' -e '/^$/d' "$here/debian-packages.txt")
[ ${#packages[@]} -gt 0 ] || { echo "setup: $here/debian-packages.txt: no packages read"; exit 1; }

backports=/etc/apt/sources.list.d/bookworm-backports.sources
if [ ! -f "$backports" ] && grep -qs bookworm /etc/os-release; then
  $SUDO tee "$backports" >/dev/null <<'SRC'
Types: deb
URIs: http://deb.debian.org/debian
Suites: bookworm-backports
Components: main
Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg
SRC
  need_update=1
fi

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
# Mesa 25 from backports: check the installed version, not just presence.
mesa_version=$(dpkg-query -W -f='${Version}' mesa-vulkan-drivers 2>/dev/null || true)
want_backports_mesa=0
if grep -qs bookworm /etc/os-release && [[ ! "$mesa_version" =~ ^2[4-9]\. ]]; then
  want_backports_mesa=1
fi

if [ ${#missing[@]} -eq 0 ] && [ $want_backports_mesa -eq 0 ]; then
  bash "$here/setup_ray_venv.sh"
  exit 0
fi

export DEBIAN_FRONTEND=noninteractive
echo "setup: installing ${missing[*]:-} $([ $want_backports_mesa -eq 1 ] && echo 'mesa-vulkan-drivers (bookworm-backports)')"
$SUDO apt-get update -qq
if [ ${#missing[@]} -gt 0 ]; then
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
if [ $want_backports_mesa -eq 1 ]; then
  # Only four packages move: mesa-vulkan-drivers and libdrm*. Fall back to Debian's
  # own Mesa quietly if backports cannot be reached; the renderer warns about it.
  $SUDO apt-get install -y -qq --no-install-recommends mesa-vulkan-drivers/bookworm-backports >/dev/null \
    || echo "setup: bookworm-backports Mesa unavailable; using Debian 12's Mesa (slower lavapipe)"
fi
bash "$here/setup_ray_venv.sh"
