# The C++ test builds' configurations, sourced by scripts/test_cpp.sh and scripts/test_cpp_example.sh:
# the example installs the library from the optimised test build, so that it is compiled once.
# cpp_configure DIR CMAKE_ARGS...: configures DIR (Ninja, no Python, the tests, warnings as errors).
CPP_RELEASE_DIR=build/cpp-release
CPP_RELEASE_ARGS=(-DCMAKE_BUILD_TYPE=Release)
CPP_SANITIZE_DIR=build/cpp-sanitize
CPP_SANITIZE_ARGS=(-DCMAKE_BUILD_TYPE=RelWithDebInfo -DVOFDEM_SANITIZE=ON)
cpp_configure() {
  local dir=$1; shift
  cmake -S . -B "$dir" -G Ninja -DVOFDEM_PYTHON=OFF -DVOFDEM_TESTS=ON -DVOFDEM_WERROR=ON "$@" >/dev/null
}
