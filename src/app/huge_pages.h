#pragma once
// Large meshes on transparent huge pages. A mesh of a million faces puts about 2 GB into the
// solver's arrays, and on 4 kB pages every first touch is a page fault (on this project's
// virtual machine about 10 microseconds each): at 955k faces the setup took 9.2 s, of which
// most was faulting pages in, and sweeps over the arrays missed the TLB. glibc (2.35 and
// newer) asks the kernel for 2 MB pages for its heap when started with the tunable
// glibc.malloc.hugetlb=1, but reads tunables only at process start; so `primo` starts itself
// again with it set (the same process id, arguments, descriptors), unless it is set already
// or PRIMO_HUGE_PAGES=0 says not to. Measured: setup at 955k faces 9.2 -> 3.4 s, at 238k
// 1.9-2.1 -> 1.2 s; the 238k frame 8% faster; peak memory 1% higher (docs/performance.md).

namespace primo::app {

// Replaces the process by itself with the tunable set, when that is wanted and possible;
// returns only when it is not (already set, turned off, or exec failed: then nothing changed).
void restart_with_huge_pages(char** argv);

}  // namespace primo::app
