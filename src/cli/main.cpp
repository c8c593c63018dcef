// Entry point placeholder; replaced by the command-line front end.
#include <cstdio>
int main() { std::puts("periflex " PERIFLEX_VERSION); return 0; }
