# Sourced by scripts/render and scripts/test: installs missing Debian packages (only when missing)
# and configures + builds the Release build in build/. Idempotent: a second run installs nothing
# and rebuilds only what changed. Functions: cohort_install_packages, cohort_build (-j the cores;
# `source scripts/setup.sh && cohort_build` rebuilds by hand), cohort_missing_packages. Run
# directly (bash scripts/setup.sh --help), it prints this and exits.
if [[ "${BASH_SOURCE[0]}" == "$0" ]]; then sed -n '1,/^[^#]/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0; fi
set -euo pipefail

COHORT_ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
COHORT_BUILD="${COHORT_BUILD:-$COHORT_ROOT/build}"

# Each Debian package and what it is for; the README lists the same.
COHORT_PACKAGES=(
  cmake g++ make pkg-config         # toolchain
  pocl-opencl-icd                   # OpenCL on the CPU (PoCL)
  ocl-icd-opencl-dev                # OpenCL ICD loader
  opencl-c-headers opencl-clhpp-headers
  libopenexr-dev                    # EXR output
  libglm-dev                        # vector maths on the host
  libtinygltf-dev                   # glTF 2.0 loading
  libtinyobjloader-dev              # OBJ + MTL loading
  libcli11-dev                      # command line
  nlohmann-json3-dev                # --stats JSON
  libfmt-dev                        # formatting
  libstb-dev                        # PNG output
  libtbb-dev                        # parallel KD-tree build
  zlib1g-dev                        # .gz scenes
  libgtest-dev                      # tests
  python3-venv                      # the venv of scripts/reference (Mitsuba, FLIP, matplotlib from PyPI)
  python3-dev                       # Python's headers: the Python module (nanobind from PyPI)
  openmpi-bin libopenmpi-dev        # mpirun cohort render: several machines (optional at build time)
  oclgrind                          # scripts/test-oclgrind: every kernel on a checking simulator (CI)
  xz-utils                          # scripts/remote/gpu-bundle --archive: the GPU bundle as .tar.xz
)
# Wanted but not needed to build and test: installed when apt can, else the feature is skipped.
COHORT_OPTIONAL_PACKAGES=(
  libembree-dev                     # Embree 3: the peer of scripts/bench on the protocol's rays
  libllvm19                         # Mitsuba's llvm_ad_rgb variant (scripts/bench, DRJIT_LIBLLVM_PATH)
)

cohort_missing_packages() {
  for p in "$@"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || echo "$p"
  done
}

cohort_install_packages() {
  local missing optional sudo=""
  mapfile -t missing < <(cohort_missing_packages "${COHORT_PACKAGES[@]}")
  mapfile -t optional < <(cohort_missing_packages "${COHORT_OPTIONAL_PACKAGES[@]}")
  [[ ${#missing[@]} -eq 0 && ${#optional[@]} -eq 0 ]] && return 0
  [[ $(id -u) -ne 0 ]] && sudo="sudo"
  if [[ ${#missing[@]} -gt 0 ]]; then
    echo "installing Debian packages: ${missing[*]}"
    $sudo apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
  fi
  if [[ ${#optional[@]} -gt 0 ]]; then
    echo "installing optional Debian packages: ${optional[*]}"
    { [[ ${#missing[@]} -gt 0 ]] || $sudo apt-get update -qq; } 2>/dev/null &&
      DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${optional[@]}" \
        >/dev/null 2>&1 || echo "optional packages not installed (${optional[*]}): their features are skipped"
  fi
}

# Configures on first use, with COHORT_CMAKE_ARGS (space-separated; CI: -DCOHORT_WERROR=ON) and
# the arguments given; again when COHORT_PYTHON_EXECUTABLE (the Python the module is built for:
# scripts/test sets the project venv's) is not the one configured.
cohort_build() {
  local jobs extra
  jobs="$(nproc 2>/dev/null || echo 2)"
  read -r -a extra <<<"${COHORT_CMAKE_ARGS:-}"
  [[ -n "${COHORT_PYTHON_EXECUTABLE:-}" ]] && extra+=("-DPython_EXECUTABLE=$COHORT_PYTHON_EXECUTABLE")
  if [[ ! -f "$COHORT_BUILD/CMakeCache.txt" ]]; then
    cmake -S "$COHORT_ROOT" -B "$COHORT_BUILD" -DCMAKE_BUILD_TYPE=Release "${extra[@]}" "$@" >/dev/null
  elif [[ -n "${COHORT_PYTHON_EXECUTABLE:-}" ]] &&
       ! grep -qx "Python_EXECUTABLE:[A-Z]*=$COHORT_PYTHON_EXECUTABLE" "$COHORT_BUILD/CMakeCache.txt"; then
    cmake -S "$COHORT_ROOT" -B "$COHORT_BUILD" "-DPython_EXECUTABLE=$COHORT_PYTHON_EXECUTABLE" >/dev/null
  fi
  cmake --build "$COHORT_BUILD" -j"$jobs"
}
