# Sourced by the scripts that run Cohort on Mesa's rusticl (scripts/test-vendors, scripts/bench-suite's
# "opencl": "rusticl" steps): cohort_rusticl unpacks Debian 12's mesa-opencl-icd (rusticl and
# clover; `apt-get download`, so nothing is registered system-wide) into
# ${XDG_CACHE_HOME:-~/.cache}/cohort/rusticl, installs the libraries it loads from Debian's packages
# (LLVM 15, libclc, the SPIR-V translator, libdrm), and exports, for the commands that follow:
#   OCL_ICD_VENDORS  a folder of the project's own ICD files: the system's (PoCL, GPU drivers) and
#                    rusticl's, so both are listed side by side and the default platforms stay as
#                    they are for every other command
#   RUSTICL_ENABLE   llvmpipe: rusticl's CPU device (Mesa's gallium driver that every machine has;
#                    32 KiB of local memory, no sub-groups, no fp64, OpenCL C 1.2)
# Returns 1 with a message (and changes nothing) when it cannot: no apt, no network.
COHORT_RUSTICL="${COHORT_RUSTICL:-${XDG_CACHE_HOME:-$HOME/.cache}/cohort/rusticl}"
# what libRusticlOpenCL.so loads (Debian 12's mesa-opencl-icd dependencies, less the ICD loader)
COHORT_RUSTICL_LIBS=(libclc-15 libclang-cpp15 libllvm15 libllvmspirvlib15 libdrm2 libdrm-amdgpu1
  libdrm-nouveau2 libdrm-radeon1 libelf1 libexpat1 libsensors5 libzstd1)

cohort_rusticl() {
  local root="$COHORT_RUSTICL" lib sudo=""
  lib="$root/root/usr/lib/x86_64-linux-gnu/libRusticlOpenCL.so.1"
  [[ $(id -u) -ne 0 ]] && sudo="sudo"
  local missing
  mapfile -t missing < <(cohort_missing_packages "${COHORT_RUSTICL_LIBS[@]}")
  if [[ ${#missing[@]} -gt 0 ]]; then
    echo "installing the libraries rusticl loads: ${missing[*]}" >&2
    { $sudo apt-get update -qq && DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends \
        "${missing[@]}" >/dev/null; } || { echo "rusticl: apt-get could not install ${missing[*]}" >&2; return 1; }
  fi
  if [[ ! -e "$lib" ]]; then
    command -v apt-get >/dev/null || { echo "rusticl: apt-get not found" >&2; return 1; }
    echo "unpacking Debian's mesa-opencl-icd (rusticl) into $root" >&2
    mkdir -p "$root/deb" || return 1
    (cd "$root/deb" && rm -f mesa-opencl-icd_*.deb && apt-get download mesa-opencl-icd >/dev/null 2>&1) ||
      { echo "rusticl: apt-get download mesa-opencl-icd failed" >&2; return 1; }
    dpkg-deb -x "$root"/deb/mesa-opencl-icd_*.deb "$root/root" || return 1
    [[ -e "$lib" ]] || { echo "rusticl: the package has no libRusticlOpenCL.so.1" >&2; return 1; }
  fi
  local icd="$root/icd" f
  rm -rf "$icd" && mkdir -p "$icd"
  for f in /etc/OpenCL/vendors/*.icd; do
    [[ -f "$f" ]] && cp "$f" "$icd/"
  done
  echo "$lib" >"$icd/rusticl.icd"
  export OCL_ICD_VENDORS="$icd"
  export RUSTICL_ENABLE=llvmpipe
}

# Run directly (not sourced): print the comment above and exit.
if [[ "${BASH_SOURCE[0]}" == "$0" ]]; then sed -n '1,/^[^#]/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0; fi
