// The target that precompiles the tests' common headers (tests/CMakeLists.txt).
int main() { return 0; }
