#!/usr/bin/env bash
# scripts/install-deps with ParaView's Python installed (docs/paraview.md): it must name the
# conflicting package, change nothing (apt-get never called) and exit non-zero; without the
# conflict it must call apt-get install with --no-remove. dpkg-query and apt-get are stand-ins
# on PATH, so nothing is installed or removed.
#   install_deps_test.sh SOURCE_DIR WORK_DIR
set -euo pipefail
src=$1 work=$2
rm -rf "$work" && mkdir -p "$work/bin"
# stand-in dpkg-query: every package installed except those listed in $work/missing
cat > "$work/bin/dpkg-query" <<'SH'
#!/usr/bin/env bash
pkg=${@: -1}
if grep -qx "$pkg" "$WORK/missing" 2>/dev/null; then exit 1; fi
if [ "$pkg" = python3-paraview ] && [ ! -e "$WORK/paraview" ]; then exit 1; fi
if [ "$pkg" = paraview-python ]; then exit 1; fi
printf 'install ok installed'
SH
# stand-in apt-get: records its arguments
cat > "$work/bin/apt-get" <<'SH'
#!/usr/bin/env bash
echo "$*" >> "$WORK/apt.log"
SH
# stand-in sudo (when not root): runs the stand-ins, never the real apt-get
printf '#!/usr/bin/env bash\nexec "$@"\n' > "$work/bin/sudo"
chmod +x "$work/bin/dpkg-query" "$work/bin/apt-get" "$work/bin/sudo"
export WORK=$work PATH="$work/bin:$PATH"
fail() { echo "FAIL: $*" >&2; exit 1; }

# 1. python3-paraview installed, libvtk9-dev missing: refuse, name it, touch nothing
echo libvtk9-dev > "$work/missing"
touch "$work/paraview"
set +e
out=$("$src/scripts/install-deps" 2>&1); rc=$?
set -e
[ $rc -ne 0 ] || fail "exit status 0 with python3-paraview installed: $out"
grep -q "python3-paraview" <<<"$out" || fail "does not name python3-paraview: $out"
grep -q "python3-vtk9" <<<"$out" || fail "does not name python3-vtk9: $out"
grep -q "docs/paraview.md" <<<"$out" || fail "does not point to docs/paraview.md: $out"
[ ! -e "$work/apt.log" ] || fail "apt-get was called: $(cat "$work/apt.log")"

# 2. no ParaView, libvtk9-dev missing: installs it, and never lets apt remove anything
rm "$work/paraview"
out=$("$src/scripts/install-deps" 2>&1) || fail "failed without ParaView: $out"
grep -q "install .*--no-remove.* libvtk9-dev" "$work/apt.log" || fail "apt-get install: $(cat "$work/apt.log")"

# 3. everything present (ParaView too): nothing to do
: > "$work/missing"; touch "$work/paraview"; rm "$work/apt.log"
out=$("$src/scripts/install-deps" 2>&1) || fail "failed with all present: $out"
grep -q "packages present" <<<"$out" || fail "$out"
[ ! -e "$work/apt.log" ] || fail "apt-get was called"
echo "install_deps_test: ok"
