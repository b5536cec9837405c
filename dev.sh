#!/usr/bin/env bash
# LightInv set-up and the two jobs, for a fresh Debian/Ubuntu machine with Python 3.11+.
#
#   ./dev.sh demo   install everything, then open the GUI on the flagship project (an open-plan
#                   office to EN 12464-1:2021 by night and daylight by day, least energy);
#                   without a display, its headless equivalent: optimise the flagship project
#   ./dev.sh test   install everything, then lint and run the whole test suite
#   ./dev.sh setup  install everything only
#
# Installs the Debian packages the GUI and its tests need (with apt-get, as root or via
# sudo) and the Python packages into .venv/ in this folder. Re-running is cheap: the
# pip step is skipped while pyproject.toml is unchanged.
set -euo pipefail
cd "$(dirname "$0")"

APT_PACKAGES=(
  xvfb xauth libgl1 libglx-mesa0 libgl1-mesa-dri libegl1 libegl-mesa0 libosmesa6
  libxkbcommon-x11-0 libxcb-cursor0 libxcb-icccm4 libxcb-keysyms1 libxcb-image0
  libxcb-randr0 libxcb-render-util0 libxcb-shape0 libxcb-xfixes0 libxcb-xkb1
  libxcb-sync1 libxcb-shm0 libx11-xcb1 libxcursor1 libxrender1 libfontconfig1
  libdbus-1-3 fonts-dejavu-core poppler-utils
)
PYTHON=${PYTHON:-python3}

say() { printf '[dev.sh] %s\n' "$*" >&2; }

setup_system() {
  command -v dpkg >/dev/null 2>&1 || { say "no dpkg: install the packages in dev.sh by hand"; return 0; }
  local missing=() p
  for p in "${APT_PACKAGES[@]}"; do
    dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p")
  done
  "$PYTHON" -c 'import ensurepip' >/dev/null 2>&1 || missing+=(python3-venv)
  [ ${#missing[@]} -eq 0 ] && return 0
  local sudo=""
  if [ "$(id -u)" -ne 0 ]; then
    if command -v sudo >/dev/null 2>&1; then sudo="sudo"; else
      say "not root and no sudo: please install: ${missing[*]}"; return 1
    fi
  fi
  say "installing Debian packages: ${missing[*]}"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends \
    "${missing[@]}" >/dev/null
}

setup_python() {
  "$PYTHON" -c 'import sys; sys.exit(sys.version_info < (3, 11))' || {
    say "Python 3.11 or newer is needed (found $("$PYTHON" --version 2>&1))"; exit 1; }
  [ -x .venv/bin/python ] || "$PYTHON" -m venv .venv
  local stamp
  stamp=$(sha256sum pyproject.toml | cut -d' ' -f1)
  if [ "$(cat .venv/.lightinv-stamp 2>/dev/null)" != "$stamp" ]; then
    say "installing Python packages into .venv"
    .venv/bin/python -m pip install -q --upgrade pip
    .venv/bin/python -m pip install -q -e '.[dev,climate,ifc,cluster]'
    echo "$stamp" > .venv/.lightinv-stamp
  fi
}

setup() { setup_system; setup_python; }

case "${1:-}" in
  setup) setup ;;
  demo)
    setup
    if [ -n "${DISPLAY:-}" ] || [ -n "${WAYLAND_DISPLAY:-}" ]; then
      say "opening the LightInv window on the flagship office project"
      exec .venv/bin/lightinv resources/projects/office-flagship.json
    fi
    say "no display: optimising the flagship office headless (lightinv-cli solve)"
    exec .venv/bin/lightinv-cli solve resources/projects/office-flagship.json
    ;;
  test)
    setup
    .venv/bin/ruff check .
    .venv/bin/ruff format --check .
    .venv/bin/lint-imports --no-cache
    # Four workers even on two cores: a GUI test spends much of its time waiting (on
    # its X server, its timers, its worker threads), so two workers left the cores
    # half idle. worksteal: a worker that runs dry takes tests queued for another.
    # One BLAS thread per worker: four workers already fill the cores, and BLAS threads
    # beyond them spin while they wait (14% more CPU on the numeric tests).
    export OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 MKL_NUM_THREADS=1
    exec .venv/bin/python -m pytest -q -n 4 --dist worksteal
    ;;
  *) echo "usage: ./dev.sh demo | test | setup" >&2; exit 2 ;;
esac
