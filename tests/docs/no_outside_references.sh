#!/usr/bin/env bash
# Fails when a tracked file points outside the project: a path into the
# planning folder beside the clone, or a tracker's issue number. A clone has
# neither, so such a reference tells its reader nothing; say the fact itself,
# or cite docs/ELEMENTS.md (element semantics) or bench/README.md (benchmark
# problems) instead.
# Run from the source tree; exits 77 (CTest: skipped) outside a git checkout.
set -uo pipefail
cd "$(dirname "$0")/../.."
if ! git rev-parse --is-inside-work-tree >/dev/null 2>&1; then
  echo "not a git checkout: nothing to check (git grep reads the tracked files)"
  exit 77
fi
# Written so that this file does not match itself.
pattern='\.\./shared|(^|[^[:alnum:]_])[Ii]ssues? #?[0-9]+'
if hits=$(git grep -nIE "$pattern"); then
  echo "These lines point outside the project (a planning path or an issue number):"
  echo "$hits"
  echo "State the fact in the comment itself, or cite docs/ELEMENTS.md or bench/README.md."
  exit 1
fi
echo "no tracked file names the planning folder or an issue number"
