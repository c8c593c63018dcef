// The object that carries the test programs' one precompiled header (tests/CMakeLists.txt):
// every test program reuses it, so it is built once per build tree.
