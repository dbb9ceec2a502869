# Sourced by the scripts that run Cohort on Intel's CPU OpenCL runtime (scripts/test-vendors,
# scripts/bench runtimes, scripts/bench-suite's "opencl": "intel" steps): cohort_intel_opencl
# installs it from PyPI (`intel-opencl-rt` and the compiler runtime it loads, `intel-cmplr-lib-rt`;
# no root needed) into a venv under
# ${XDG_CACHE_HOME:-~/.cache}/cohort/intel-opencl-rt, and exports, for the commands that follow:
#   OCL_ICD_VENDORS  a folder of the project's own ICD files: the system's (/etc/OpenCL/vendors:
#                    PoCL, GPU drivers) and Intel's, so both runtimes are listed side by side
#   LD_PRELOAD       the runtime's oneTBB 2023 (libtbb.so.12): Cohort itself links Debian's oneTBB
#                    2021.8 under the same soname, which lacks symbols libintelocl.so needs; oneTBB
#                    is backward compatible, so the whole process uses the newer one
# Returns 1 with a message (and changes nothing) when it cannot: no network, no python3.
COHORT_INTEL_OPENCL="${COHORT_INTEL_OPENCL:-${XDG_CACHE_HOME:-$HOME/.cache}/cohort/intel-opencl-rt}"

cohort_intel_opencl() {
  local venv="$COHORT_INTEL_OPENCL" lib icd
  lib="$venv/lib"
  if [[ ! -f "$lib/libintelocl.so" || ! -f "$lib/libimf.so" ]]; then
    command -v python3 >/dev/null || { echo "Intel OpenCL: python3 not found" >&2; return 1; }
    echo "installing Intel's CPU OpenCL runtime (PyPI intel-opencl-rt, ~300 MB) into $venv" >&2
    { [[ -x "$venv/bin/pip" ]] || python3 -m venv "$venv"; } || return 1
    # few retries: a machine without network skips quickly
    "$venv/bin/pip" install --quiet --retries 1 --timeout 15 intel-opencl-rt intel-cmplr-lib-rt ||
      { echo "Intel OpenCL: pip could not install intel-opencl-rt" >&2; return 1; }
  fi
  icd="$venv/icd"
  rm -rf "$icd" && mkdir -p "$icd"
  # the system's ICDs, listed as they are now (a GPU driver installed later is picked up next time)
  local f
  for f in /etc/OpenCL/vendors/*.icd; do
    [[ -f "$f" ]] && cp "$f" "$icd/"
  done
  echo "$lib/libintelocl.so" >"$icd/intel-cpu.icd"
  export OCL_ICD_VENDORS="$icd"
  export LD_PRELOAD="$lib/libtbb.so.12${LD_PRELOAD:+:$LD_PRELOAD}"
}

# A --device spec (or COHORT_DEVICE) that matches one CPU runtime's platform only: pocl or intel.
cohort_runtime_device() {
  case "$1" in pocl) echo "portable computing" ;; intel) echo "intel(r) opencl" ;; *) echo "$1" ;; esac
}

# Run directly (not sourced): print the comment above and exit.
if [[ "${BASH_SOURCE[0]}" == "$0" ]]; then sed -n '1,/^[^#]/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0; fi
