#!/bin/sh
# Fails when the sources or docs cite a document that is not in the repository:
# a design note or reference file of the workspace the project grew in
# ("DESIGN §", "reference/<file>", "../shared", "/work/shared", the "seed NNN"
# papers by number, the workspace's physics and style notes). Cite the
# published source instead (docs/references.md) or a file inside the repository.
# "dfc/reference/" (the include path of reference_servers) is not a citation.
#
#   no_outside_references.sh REPO_ROOT
root=${1:?usage: no_outside_references.sh REPO_ROOT}
cd "$root" || exit 2
pattern='DESIGN|\.\./shared|/work/shared|(?<!dfc/)reference/|(?i:\bseeds? 0[0-9]{2}\b)|\b(dem|fdm)-physics\.md|coupling-and-zeromq|STYLE(\.md)? ?§|STYLE\.md'
hits=$(grep -rnP "$pattern" \
  --include='*.cpp' --include='*.hpp' --include='*.h' --include='*.md' --include='*.py' \
  --include='*.txt' --include='*.json' --include='*.cmake' --include='*.cff' \
  --exclude-dir=.git --exclude-dir=build --exclude-dir='build-*' --exclude-dir=results --exclude-dir=e2e-output .)
if [ -n "$hits" ]; then
  printf '%s\n' "$hits"
  printf '\n%s\n' "FAIL: the lines above cite documents outside the repository; cite the published source (docs/references.md) or a file in the repository." >&2
  exit 1
fi
echo "OK: no citation of a document outside the repository"
