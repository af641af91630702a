# Sourced by bench/peers/run-mitsuba-peer and run-drjit-peer: the venv build/venv-peers with Mitsuba 3
# (which brings Dr.Jit 1.x) and numpy from PyPI, Debian's libllvm19 for Dr.Jit's LLVM backend (Debian
# 12's default libLLVM 15 is too old for it), DRJIT_LIBLLVM_PATH pointing at it. Exit 2 with one line
# when the network or libllvm19 is missing. Not part of `make test`.
venv=build/venv-peers
fail() { echo "bench-peers: $*" >&2; exit 2; }

if [[ "$(dpkg-query -W -f='${Status}' libllvm19 2>/dev/null || true)" != "install ok installed" ]]; then
  sudo_cmd=()
  if [[ $(id -u) -ne 0 ]]; then
    command -v sudo >/dev/null || fail "libllvm19 is missing and not root; install it (apt-get install libllvm19) or run as root"
    sudo_cmd=(sudo)
  fi
  echo "bench-peers: installing libllvm19"
  export DEBIAN_FRONTEND=noninteractive
  { "${sudo_cmd[@]}" apt-get update -qq && "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends libllvm19; } >/dev/null 2>&1 \
    || fail "cannot install libllvm19 (no network, or no such package in this Debian's sources); Dr.Jit needs LLVM >= 16"
fi
libllvm=$(dpkg -L libllvm19 | grep -m1 '/libLLVM.*\.so' || true)
[[ -n "$libllvm" && -e "$libllvm" ]] || fail "libllvm19 is installed but its libLLVM*.so was not found (dpkg -L libllvm19)"

if [[ ! -x "$venv/bin/python" ]] || ! "$venv/bin/python" -c 'import mitsuba, drjit, numpy' 2>/dev/null; then
  python3 -m venv "$venv" 2>/dev/null || fail "cannot create $venv (apt-get install python3-venv)"
  "$venv/bin/pip" install -q --disable-pip-version-check mitsuba numpy >/dev/null 2>&1 \
    || fail "cannot install mitsuba and numpy from PyPI into $venv (no network?)"
fi

export DRJIT_LIBLLVM_PATH="$libllvm"
