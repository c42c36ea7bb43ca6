// SystemC's library provides main() and calls sc_main() from it; rtsim's programs have their own
// main() and start simulations themselves, so sc_main is never called. Linked into every program
// that does not define its own (the systemc_* tests do).
extern "C" int sc_main(int, char*[]) { return 0; }
