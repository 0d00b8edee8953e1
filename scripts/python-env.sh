# Sourced (not run) by the scripts that run python: a virtual environment of the project's own,
# target/venv, with tests/python/requirements.txt installed, put first on PATH so that `python3` is the
# environment's (the with-vcan VM inherits PATH). Nothing is installed into the system interpreter.
# SKIP_PIP=1 skips the install (an earlier script of the same run installed it). CANOPEN_VENV moves it.
CANOPEN_VENV="${CANOPEN_VENV:-$PWD/target/venv}"
if [[ ! -x "$CANOPEN_VENV/bin/python3" ]]; then
    python3 -m venv "$CANOPEN_VENV"
fi
export VIRTUAL_ENV="$CANOPEN_VENV"
export PATH="$CANOPEN_VENV/bin:$PATH"
if [[ "${SKIP_PIP:-0}" != 1 ]]; then
    python3 -m pip install --quiet --disable-pip-version-check -r tests/python/requirements.txt
fi
