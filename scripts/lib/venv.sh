# Sourced by the scripts that need Python packages from PyPI (reference images, benchmark peers,
# charts): cohort_venv PACKAGE... makes sure $COHORT_VENV (default build/venv) exists and can import
# them, installing what is missing; MODULE:PACKAGE where the import name differs from PyPI's
# (flip_evaluator:flip-evaluator). Returns 1 with a message when it cannot (no python3 or no
# network), so callers can skip their Python part.
COHORT_VENV="${COHORT_VENV:-$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)/build/venv}"

cohort_venv() {
  if ! command -v python3 >/dev/null; then
    echo "python3 not found" >&2
    return 1
  fi
  if [[ ! -x "$COHORT_VENV/bin/python" ]]; then
    echo "creating $COHORT_VENV" >&2
    python3 -m venv "$COHORT_VENV" || return 1
  fi
  local imports=() packages=() spec
  for spec in "$@"; do
    imports+=("${spec%%:*}")
    packages+=("${spec#*:}")
  done
  if ! "$COHORT_VENV/bin/python" -c "import $(IFS=,; echo "${imports[*]}")" 2>/dev/null; then
    echo "installing ${packages[*]} into $COHORT_VENV" >&2
    "$COHORT_VENV/bin/pip" install --quiet --upgrade pip >/dev/null 2>&1 || true
    # few retries: a machine without network (a GPU box) should skip quickly, not hang
    "$COHORT_VENV/bin/pip" install --quiet --retries 1 --timeout 15 "${packages[@]}" || return 1
  fi
}
