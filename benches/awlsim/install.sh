#!/usr/bin/env bash
# Installs awlsim 0.77.1 twice under target/, for the benchmarks that measure it beside awl:
# target/awlsim-venv from pip as it comes (pure Python), and target/awlsim-cython-venv built
# from its source archive with its Cython core (Cython before 3: awlsim 0.77.1's modules do
# not build with later ones). The build compiles some hundred C modules: several minutes.
# Usage: benches/awlsim/install.sh [pip|cython]  (both without an argument)
set -euo pipefail
cd "$(dirname "$0")/../.."
awlsim_version=0.77.1
which=${1:-both}

if [ "$which" != cython ] && [ ! -x target/awlsim-venv/bin/awlsim-test ]; then
    python3 -m venv target/awlsim-venv
    target/awlsim-venv/bin/pip install --quiet "awlsim==$awlsim_version"
fi

# Through awlsim's loader, as benches/awlsim/driver.py imports it: `import awlsim.core.main`
# succeeds without the Cython modules too.
cython_built() {
    AWLSIM_CYTHON=2 target/awlsim-cython-venv/bin/python3 -c "import awlsim_loader.core" 2>/dev/null
}
if [ "$which" != pip ] && ! cython_built; then
    python3 -m venv target/awlsim-cython-venv
    target/awlsim-cython-venv/bin/pip install --quiet "cython<3" setuptools wheel
    # Not from pip's wheel cache: a wheel built there before without Cython would be taken.
    AWLSIM_CYTHON_BUILD=1 target/awlsim-cython-venv/bin/pip install --quiet --no-cache-dir \
        --no-build-isolation --no-binary awlsim "awlsim==$awlsim_version"
fi
echo "awlsim $awlsim_version ready under target/ ($which)"
