// How the process's heap treats the memory libtorch frees. libtorch's CPU
// allocator hands every activation back to glibc's malloc after each pass;
// glibc unmaps blocks above its mmap threshold and trims a large free top
// of the heap, so the next pass faults the same megabytes in again, page by
// page. On a virtual machine a fault is expensive: at 256 x 256 GS-DepthNet's
// forward pass took 207 ms of CPU that way, 55 ms with the memory kept
// (bench_gs_depthnet, one thread). No torch in this header.
#pragma once

namespace touchcloud::learning {

// Raises glibc's mmap threshold to its maximum (32 MiB) and its trim
// threshold to 1 GiB for the whole process, so freed tensors stay in the
// heap for the next pass. Idempotent; the network stages call it when they
// start. The cost: up to the largest pass's working set stays mapped.
void keep_freed_memory_for_reuse();

}  // namespace touchcloud::learning
