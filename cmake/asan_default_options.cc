// Compiled into every executable of the sanitizer build (cmake/sanitizer_defaults.cmake): the
// options AddressSanitizer reads before ASAN_OPTIONS, which still overrides them.
//
// intercept_tls_get_addr=0: GCC 12's sanitizer runtime (and LLVM's up to 16) takes a dynamic
// TLS block whose address modulo 4096 is 16 for one carrying glibc 2.19's header, and reads
// the two words before it as the block's range (google/sanitizers issue 1322). Since glibc
// 2.25 there is no such header, so when a malloc'd block lands on that offset by chance,
// LeakSanitizer's exit check scans a wild range and dies ("Tracer caught signal 11"). Only
// libraries loaded with dlopen have dynamic TLS here (OpenImageIO and OpenEXR behind
// librelief_images.so, Mesa's drivers), and the check failed about one run in three once several
// processes wrote EXR files side by side (tests/slurm/slurm_test.sh). Without the interceptor
// LeakSanitizer does not scan those libraries' dynamic TLS blocks: a block reachable only from
// there would be reported as a leak, never hidden.
extern "C" __attribute__((visibility("default"), used)) const char* __asan_default_options() {
  return "intercept_tls_get_addr=0";
}
