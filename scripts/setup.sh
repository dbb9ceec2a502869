# Sourced by scripts/render and scripts/test: installs missing Debian packages (only when missing)
# and configures + builds the Release build in build/. Idempotent: a second run installs nothing
# and rebuilds only what changed.
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
  openmpi-bin libopenmpi-dev        # mpirun cohort render: several machines (optional at build time)
)

cohort_install_packages() {
  local missing=()
  for p in "${COHORT_PACKAGES[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  [[ ${#missing[@]} -eq 0 ]] && return 0
  echo "installing Debian packages: ${missing[*]}"
  local sudo=""
  [[ $(id -u) -ne 0 ]] && sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
}

cohort_build() {
  local jobs
  jobs="$(nproc 2>/dev/null || echo 2)"
  if [[ ! -f "$COHORT_BUILD/CMakeCache.txt" ]]; then
    cmake -S "$COHORT_ROOT" -B "$COHORT_BUILD" -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
  fi
  cmake --build "$COHORT_BUILD" -j"$jobs"
}
