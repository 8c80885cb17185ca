// Compiled into penumbra_asan only. Makes dlclose() keep every library mapped until the process
// exits, so that LeakSanitizer's exit check sees the GL driver as it was.
//
// Without it every run that opens a GL context ends in a LeakSanitizer report (112 bytes in 2
// allocations, exit 86): eglTerminate() unloads Mesa's swrast_dri.so, whose globals were the only
// pointers to two blocks it had allocated, so those blocks look lost, and their allocation stacks
// point into an unmapped library ("<unknown module>"), which no suppression can name precisely.
// With the driver kept mapped the blocks stay reachable and nothing is reported; a block the
// driver (or anything else) really loses is still reported, with its library's name.
extern "C" int dlclose(void* /*handle*/) { return 0; }
