#include <iostream>
int main() { std::cout << "rtsim\n"; return 0; }
