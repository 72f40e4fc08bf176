#!/bin/bash
# ctest "install": `cmake --install` into a temporary prefix, the prefix moved elsewhere, then
# the installed packlab makes a plot with its own copy of the plot package (found relative to
# the binary, not through the sources it was built from) and the installed Python module
# imports from the prefix. Usage: test_install.sh BUILD_DIR
set -euo pipefail
build=$1
tmp=$(mktemp -d "${TMPDIR:-/tmp}/packlab-install-XXXXXX")
trap 'rm -rf "$tmp"' EXIT
cmake --install "$build" --prefix "$tmp/first" >/dev/null
mv "$tmp/first" "$tmp/moved"  # relocatable: nothing points back at the first prefix
prefix=$tmp/moved
test -x "$prefix/bin/packlab"
test -f "$prefix/lib/packlab/python/packlab/plot/__main__.py"

# A python3 that records the PYTHONPATH packlab gives it, then runs Debian's.
cat >"$tmp/python3" <<EOF
#!/bin/bash
echo "\$PYTHONPATH" >>"$tmp/pythonpath.log"
exec /usr/bin/python3 "\$@"
EOF
chmod +x "$tmp/python3"
cd "$tmp"
env -u PACKLAB_PYTHONPATH -u PYTHONPATH PACKLAB_PYTHON="$tmp/python3" MPLBACKEND=Agg \
  "$prefix/bin/packlab" generate fba --particles 60 --seed 1 --quiet --out "$tmp/fba" 2>"$tmp/stderr" || {
  cat "$tmp/stderr"
  exit 1
}
if [ ! -s "$tmp/fba/fba.png" ] || grep -q "plots skipped" "$tmp/stderr"; then
  echo "install: no plot from the installed packlab:"
  cat "$tmp/stderr"
  exit 1
fi
if ! grep -q "^$prefix/lib/packlab/python" "$tmp/pythonpath.log"; then
  echo "install: the plot package was not taken from the prefix:"
  cat "$tmp/pythonpath.log"
  exit 1
fi

# The Python module from the prefix, where it was built.
if ls "$prefix/lib/packlab/python/packlab/" | grep -q '^_core'; then
  env -u PYTHONPATH PYTHONPATH="$prefix/lib/packlab/python" /usr/bin/python3 -c "
import packlab
assert packlab.__file__.startswith('$prefix'), packlab.__file__
p = packlab.generate_lattice(type='sc', cells=(2, 2, 2), radius=0.5)
assert len(p) == 8
"
fi
echo "install: ok ($prefix)"
