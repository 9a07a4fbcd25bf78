#!/bin/sh
# Package the VS Code extension (editors/vscode) as build/cncc-gcode.vsix.
#
#   scripts/package-vscode.sh [OUT.vsix]
#
# Needs node and npm; fetches vscode-languageclient and @vscode/vsce from the npm registry
# into a scratch copy (the tree gets no node_modules).  Without node or npm it says so and
# exits 0, so CI can call it everywhere.  Exit 1 when packaging fails.
set -eu
here=$(cd "$(dirname "$0")/.." && pwd)
out=${1:-"$here/build/cncc-gcode.vsix"}
case "$out" in /*) ;; *) out="$PWD/$out" ;; esac
if ! command -v node >/dev/null 2>&1 || ! command -v npm >/dev/null 2>&1; then
    echo "package-vscode: node/npm not found; the .vsix is not built (skipped)"
    exit 0
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cp -R "$here/editors/vscode/." "$work/"
cd "$work"
npm install --omit=dev --no-audit --no-fund --loglevel=error >/dev/null
mkdir -p "$(dirname "$out")"
npx --yes @vscode/vsce@3 package --allow-missing-repository --out "$out" >/dev/null
unzip -l "$out" | grep -q "extension/package.json" || { echo "package-vscode: $out has no package.json" >&2; exit 1; }
echo "package-vscode: wrote $out"
