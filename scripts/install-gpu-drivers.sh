#!/usr/bin/env bash
# Installs Mesa's software GPU drivers so the GPU tests have adapters on a
# machine without a GPU: lavapipe (Vulkan) and llvmpipe via EGL (GL).
# Idempotent. Exit status 0 when the drivers are installed, 1 (with a warning) when
# they could not be installed; callers keep going (scripts/test-all.sh then runs
# the GPU tests without PHOTOSOLID_REQUIRE_GPU=1, so they skip without an adapter).
# Usage: bash scripts/install-gpu-drivers.sh
set -u

pkgs="mesa-vulkan-drivers libvulkan1 libegl-mesa0 libegl1 libgl1-mesa-dri"

missing=""
for p in $pkgs; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing="$missing $p"
  fi
done

if [ -z "$missing" ]; then
  echo "gpu drivers: already installed ($pkgs)"
  exit 0
fi

if ! command -v apt-get >/dev/null 2>&1; then
  echo "WARNING: gpu drivers: apt-get not available; missing:$missing (GPU tests will skip)" >&2
  exit 1
fi

SUDO=""
if [ "$(id -u)" != "0" ]; then
  if command -v sudo >/dev/null 2>&1; then SUDO="sudo -n"; else
    echo "WARNING: gpu drivers: not root and no sudo; missing:$missing (GPU tests will skip)" >&2
    exit 1
  fi
fi

echo "gpu drivers: installing$missing"
if ! { $SUDO apt-get update -qq && DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends $missing; } >/tmp/photosolid-gpu-drivers.log 2>&1; then
  echo "WARNING: gpu drivers: apt-get failed (see /tmp/photosolid-gpu-drivers.log); GPU tests will skip" >&2
  tail -n 5 /tmp/photosolid-gpu-drivers.log >&2 || true
  exit 1
fi
echo "gpu drivers: installed"
exit 0
