#ifndef cycloid_process_heap_h
#define cycloid_process_heap_h

#include <cstddef>

namespace cycloid
{
  namespace process
  {
    /**
     * Let freed matrix-sized blocks go back to the system.
     *
     * Debian's SuperLU_DIST, which deal.II links through PETSc, carries
     * CombBLAS, whose static initialiser calls `mallopt(M_MMAP_MAX, 0)` and
     * `mallopt(M_TRIM_THRESHOLD, -1)` when the library is loaded, before
     * main(). From then on glibc never maps a large block on its own and
     * never shrinks the heap: the matrix, its pattern and the AMG set-up's
     * products of an active-set iteration stay resident after they are
     * freed, and the next iteration's blocks fit only in part into the
     * holes. On the 3D seed case that was about a tenth of the peak
     * (doc/solver-reuse.md, "Memory: a library that kept every freed
     * block").
     *
     * This call maps blocks of at least @p mmap_threshold bytes (at most
     * 32 MB, glibc's limit) on their own again, so that they are unmapped
     * when freed. Those are the matrix, its pattern and the AMG set-up's
     * products. Vectors, which an AMG cycle allocates and frees at every
     * application, stay in the heap up to 4 M DoFs per rank and are not
     * faulted in anew each time. The heap is not trimmed at every free, as
     * the libraries left it; give_back_freed_pages() gives its free pages
     * back where a large structure has just been replaced.
     *
     * The environment variable `CYCLOID_MMAP_THRESHOLD` (bytes; 0 keeps the
     * libraries' setting) overrides @p mmap_threshold, for measurements.
     * Call it once, first thing in main(), after restart_with_huge_pages().
     * Without glibc it does nothing.
     */
    void
    release_freed_memory(std::size_t mmap_threshold = 32u << 20);

    /** The threshold release_freed_memory() set [bytes]; 0 if it kept the
     * libraries' setting or was not called. */
    std::size_t
    mmap_threshold();

    /** Free heap [bytes] from which give_back_freed_pages() acts. Small
     * runs free their whole system at each active set (at most about 170
     * MB a rank: a 2D scene of 148 k DoFs on one rank) and ran 9 % (3D,
     * 100 k DoFs) to 25 % (that 2D scene) slower with the trim, each page
     * given back being faulted in anew; the 3D seed case frees 235-426 MB
     * a rank, where the peak falls by a tenth (doc/solver-reuse.md). */
    constexpr std::size_t give_back_threshold = 192u << 20;

    /**
     * Give the whole free pages inside the heap back to the system
     * (`malloc_trim(0)`), if release_freed_memory() set a threshold and at
     * least give_back_threshold bytes of the heap are free.
     *
     * The blocks below the threshold stay in the heap: a dynamic sparsity
     * pattern's rows, the constraints' lines, the index sets. When a new
     * pattern or a new set of constraints replaces the old, their freed
     * blocks leave holes of hundreds of MB that the libraries' setting never
     * returns, and the AMG set-up that follows peaks on top of them. On the
     * 3D seed case, calling this once the constraints are rebuilt took a
     * tenth off the peak (doc/solver-reuse.md, "The holes of small
     * blocks"). Pages used again are faulted in anew, and each page given
     * back inside one of the heap's 2 MB huge pages splits it into 4 kB
     * pages, so call it where a large structure has just been freed, not in
     * a loop. Without glibc it does nothing.
     */
    void
    give_back_freed_pages();

    /**
     * Start this program again, once, with glibc's tunable
     * `glibc.malloc.hugetlb=1` (transparent huge pages for the blocks
     * glibc maps), unless `GLIBC_TUNABLES` already names it,
     * `CYCLOID_MMAP_THRESHOLD` is 0 or the program runs under valgrind
     * (which a restart would leave behind).
     *
     * A mapped block is new memory each time: every active-set iteration
     * faults its matrix and AMG products in afresh. In 4 kB pages that made
     * the 3D seed case 14 % slower; in 2 MB pages it costs nothing
     * measurable. glibc reads its tunables only when a process starts, and
     * the kernel here gives huge pages only where a program asks for them
     * (`madvise`), hence the restart. Call it first thing in main(), before
     * MPI is initialised; @p argv is main()'s. If the restart fails, the
     * program goes on with small pages.
     */
    void
    restart_with_huge_pages(char **argv);
  } // namespace process
} // namespace cycloid

#endif
