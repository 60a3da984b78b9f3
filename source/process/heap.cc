#include <cycloid/process/heap.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#if defined(__GLIBC__)
#  include <malloc.h>
#  include <unistd.h>
#endif

namespace cycloid
{
  namespace process
  {
    namespace
    {
      std::size_t threshold_set = 0;

      /** The threshold to use [bytes]: @p requested unless the environment
       * says otherwise. A value that is not a number of bytes is ignored,
       * with a warning if @p warn: this runs before main() can report
       * errors, and once per process is enough. */
      std::size_t
      threshold(const std::size_t requested, const bool warn = false)
      {
        const char *value = std::getenv("CYCLOID_MMAP_THRESHOLD");
        if (value == nullptr)
          return requested;
        char                    *end   = nullptr;
        const unsigned long long bytes = std::strtoull(value, &end, 10);
        if (end == value || *end != '\0')
          {
            if (warn)
              std::fprintf(
                stderr,
                "cycloid-contact: CYCLOID_MMAP_THRESHOLD=%s is not a "
                "number of bytes; it is ignored.\n",
                value);
            return requested;
          }
        return bytes;
      }



      /** Whether the environment keeps the libraries' heap setting
       * (`CYCLOID_MMAP_THRESHOLD=0`, for measurements of the old
       * behaviour). */
      bool
      libraries_setting_kept()
      {
        return threshold(1) == 0;
      }
    } // namespace



    void
    restart_with_huge_pages(char **argv)
    {
#if defined(__GLIBC__)
      if (libraries_setting_kept())
        return;
      const char       *tunables = std::getenv("GLIBC_TUNABLES");
      const std::string current  = tunables ? tunables : "";
      if (current.find("glibc.malloc.hugetlb") != std::string::npos)
        return;
      // Under valgrind the restarted program would run without it.
      const char *preload = std::getenv("LD_PRELOAD");
      if (preload && std::strstr(preload, "vgpreload"))
        return;
      const std::string wanted =
        (current.empty() ? "" : current + ":") + "glibc.malloc.hugetlb=1";
      if (setenv("GLIBC_TUNABLES", wanted.c_str(), 1) != 0)
        return;
      execv("/proc/self/exe", argv);
      // Only reached if the program could not be started again: it runs on
      // with small pages, which costs time, not results.
#else
      (void)argv;
#endif
    }



    void
    release_freed_memory(const std::size_t mmap_threshold)
    {
      const std::size_t bytes = threshold(mmap_threshold, true);
      if (bytes == 0)
        return;
#if defined(__GLIBC__)
      // glibc's own default for the number of mapped blocks. The heap is
      // not trimmed at every free, as the libraries left it: trimming each
      // time gave back the vectors that every AMG cycle allocates anew, and
      // faulting them in again cost time (give_back_freed_pages() trims at
      // chosen moments instead).
      if (mallopt(M_MMAP_MAX, 65536) == 1 &&
          mallopt(M_MMAP_THRESHOLD, static_cast<int>(bytes)) == 1)
        threshold_set = bytes;
#endif
    }



    std::size_t
    mmap_threshold()
    {
      return threshold_set;
    }



    void
    give_back_freed_pages()
    {
#if defined(__GLIBC__)
      if (threshold_set == 0)
        return;
      // Only where there is much to give (give_back_threshold says why).
      if (mallinfo2().fordblks >= give_back_threshold)
        malloc_trim(0);
#endif
    }
  } // namespace process
} // namespace cycloid
