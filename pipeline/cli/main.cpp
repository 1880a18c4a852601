#include <malloc.h>

#include <csignal>
#include <iostream>

#include "pipeline/cli/commands.h"

namespace {

// glibc serves blocks from 128 kB up (a mesh's arrays, an encoded file) with
// mmap and returns them with munmap. Between threads of one process (batch
// --jobs 2, run of several designs) every munmap stops the other core to
// flush its TLB, and every fresh block page-faults again: --jobs 2 of the
// bench/batch_overhead.sh sweep took 3.9-5.1 s where two separate processes
// took 3.9-4.7 s. Keeping blocks below 64 MiB in the heap, and up to 256 MiB
// of freed heap before trimming, makes it 3.7-3.8 s (bench/README.md,
// "Batches"). Larger blocks (the 8.7e6-triangle vessel's) still go back at once.
void keep_freed_blocks_for_reuse() {
  mallopt(M_MMAP_THRESHOLD, 64 << 20);
  mallopt(M_TRIM_THRESHOLD, 256 << 20);
}

// A write past the file size limit (`ulimit -f`, RLIMIT_FSIZE) raises
// SIGXFSZ, whose default ends the process with a core and no message. Ignored,
// the write fails with EFBIG instead: the job reports it and exits 5 (an
// environment failure, nothing half-written left under the file's name).
void fail_writes_past_the_size_limit() { std::signal(SIGXFSZ, SIG_IGN); }

}  // namespace

int main(int argc, char** argv) {
  keep_freed_blocks_for_reuse();
  fail_writes_past_the_size_limit();
  return fabmesh::cli::run_app(argc, argv, {std::cout, std::cerr});
}
