# Sourced by bench/peers/run-mitsuba-peer and run-drjit-peer: the venv build/venv-peers with Mitsuba 3
# (which brings Dr.Jit 1.x) and numpy from PyPI, Debian's libllvm19 for Dr.Jit's LLVM backend (Debian
# 12's default libLLVM 15 is too old for it), DRJIT_LIBLLVM_PATH pointing at it. Exit 2 with one line
# when the network or libllvm19 is missing. Not part of `make test`.
# The caller sets peer_modules (the Python modules it imports) and need_llvm (0: the CUDA backend
# alone, which needs no libLLVM). On a machine without network (a lent GPU machine), wheels of those
# modules in $BRDFCL_PEER_WHEELS (pip download drjit numpy -d DIR) are installed from there.
venv=build/venv-peers
fail() { echo "bench-peers: $*" >&2; exit 2; }
: "${peer_modules:=mitsuba numpy}" "${need_llvm:=1}"

if [[ "$(dpkg-query -W -f='${Status}' libllvm19 2>/dev/null || true)" != "install ok installed" && "$need_llvm" == 1 ]]; then
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
libllvm=$(dpkg -L libllvm19 2>/dev/null | grep -m1 '/libLLVM.*\.so' || true)
if [[ "$need_llvm" == 1 ]]; then
  [[ -n "$libllvm" && -e "$libllvm" ]] || fail "libllvm19 is installed but its libLLVM*.so was not found (dpkg -L libllvm19)"
fi

imports=$(echo "$peer_modules" | tr ' ' ',')
if [[ ! -x "$venv/bin/python" ]] || ! "$venv/bin/python" -c "import $imports" 2>/dev/null; then
  python3 -m venv "$venv" 2>/dev/null || fail "cannot create $venv (apt-get install python3-venv)"
  if [[ -n "${BRDFCL_PEER_WHEELS:-}" ]]; then
    # shellcheck disable=SC2086
    "$venv/bin/pip" install -q --disable-pip-version-check --no-index --find-links "$BRDFCL_PEER_WHEELS" $peer_modules >/dev/null 2>&1 \
      || fail "cannot install $peer_modules from the wheels in $BRDFCL_PEER_WHEELS (BRDFCL_PEER_WHEELS)"
  else
    "$venv/bin/pip" install -q --disable-pip-version-check mitsuba numpy >/dev/null 2>&1 \
      || fail "cannot install mitsuba and numpy from PyPI into $venv (no network? then set BRDFCL_PEER_WHEELS)"
  fi
fi

if [[ -n "$libllvm" ]]; then export DRJIT_LIBLLVM_PATH="$libllvm"; fi
