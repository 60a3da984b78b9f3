#!/usr/bin/env bash
# Draw what a run's output directory holds as PNG files in OUTPUT_DIR/plots/
# (and plots/index.json), see scripts/plot.py.   Usage: scripts/plot.sh OUTPUT_DIR
# Debian's python3 (numpy, matplotlib) on purpose: a python3 earlier on PATH
# (a virtualenv, pyenv) may lack them.
set -euo pipefail
exec /usr/bin/python3 "$(dirname "${BASH_SOURCE[0]}")/plot.py" "$@"
