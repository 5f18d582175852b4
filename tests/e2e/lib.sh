# Shared by the end-to-end scripts (sourced before they change into their work folder): fail, and
# expect_refusal. Each script sets what a refused command must not leave behind (refusal_outputs) and
# the files its cases make before a refusal (refusal_inputs: grep patterns); anything else is a stray.
fail() { echo "FAIL: $*" >&2; exit 1; }
refusal_outputs=(out.h5)
refusal_inputs=()

# expect_refusal "what the message must name" command...: exit 2, the message names the fault, no output
# and no temporary file left behind.
expect_refusal() {
  local needle=$1; shift
  set +e; "$@" >stdout.txt 2>stderr.txt; local rc=$?; set -e
  cat stderr.txt
  [[ $rc -eq 2 ]] || fail "exit $rc, expected 2: $*"
  grep -qF -- "$needle" stderr.txt || fail "message does not name '$needle': $*"
  local f
  for f in "${refusal_outputs[@]}"; do [[ ! -e $f ]] || fail "output file left behind ($f): $*"; done
  local keep=(-e stdout.txt -e stderr.txt)
  for f in "${refusal_inputs[@]}"; do keep+=(-e "$f"); done
  [[ -z $(ls -A . | grep -v "${keep[@]}" || true) ]] || fail "stray files left behind: $(ls -A)"
}
