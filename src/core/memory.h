// Peak resident memory of this process, resettable so each run of a sweep gets its own peak.
#pragma once

namespace fairshape {

// Resets the kernel's high-water mark (Linux >= 4.0, /proc/self/clear_refs); false if unsupported.
bool reset_peak_rss();
// Peak resident set size in MiB since start or the last successful reset (VmHWM).
double peak_rss_mb();
// Resident set size now, in MiB (VmRSS), after returning the allocator's free memory to the
// system (so memory freed by an earlier step does not hide the next step's growth).
double trimmed_rss_mb();
// Returns the allocator's free memory to the system (glibc keeps freed pages of a large,
// fragmented heap resident: a supervisor that validated a level-5 sweep held 2.2 GB it had freed).
void release_free_memory();
// Memory this process could still take, in MiB: the kernel's MemAvailable plus free swap, capped by
// the cgroup (v2) limit when one is set; -1 when neither can be read.
double available_memory_mb();

}  // namespace fairshape
