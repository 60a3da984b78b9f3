#ifndef cycloid_results_state_buffer_h
#define cycloid_results_state_buffer_h

#include <cycloid/results/stage_state.h>

#include <vector>

namespace cycloid
{
  namespace results
  {
    /**
     * @brief A StageState as one flat buffer of doubles, to send a state
     * solved on one rank to another (the phase groups of a sweep send their
     * states to world rank 0, which writes every file).
     *
     * Layout: the scalar fields of the state, a flag for a failed error
     * estimate (its message stays behind), the number of pins, then the
     * scalar fields of each pin in order. Integers travel as doubles (exact
     * below 2^53, far above any step, iteration or DoF count). pack() and
     * unpack() read one list of fields (source/results/state_buffer.cc), so
     * a field added to StageState or PinState is added there once;
     * tests/test_results.cc checks the round trip of every field and fails
     * when a struct grows without it.
     */
    struct StateBuffer
    {
      /** @p state as a buffer. */
      static std::vector<double>
      pack(const StageState &state);

      /** The state packed into the @p size doubles at @p data (throws if
       * the size does not match the layout). */
      static StageState
      unpack(const double *data, const unsigned int size);

      /** The state packed into @p buffer. */
      static StageState
      unpack(const std::vector<double> &buffer)
      {
        return unpack(buffer.data(), buffer.size());
      }
    };
  } // namespace results
} // namespace cycloid

#endif
