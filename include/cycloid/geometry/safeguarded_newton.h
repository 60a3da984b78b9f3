#ifndef cycloid_geometry_safeguarded_newton_h
#define cycloid_geometry_safeguarded_newton_h

#include <cmath>

namespace cycloid
{
  namespace geometry
  {
    /** What safeguarded_newton() found. */
    struct NewtonResult
    {
      /** The last iterate. */
      double x = 0;
      /** True if the last step was below the tolerance. */
      bool converged = false;
    };

    /**
     * @brief A root of a smooth scalar function by Newton's method, kept
     * safe by a bracket: the one root finder of the project (the closest
     * point on a disc's profile, the force of a line contact at a given
     * approach).
     *
     * @p f(x, value, slope) evaluates the function and its derivative. If
     * @p bracketed, [@p lower, @p upper] holds a sign change, value(lower)
     * <= 0 <= value(upper) (the caller knows it; the bounds are not
     * evaluated): the bracket shrinks to each iterate's side, and a Newton
     * step that leaves it, or a slope <= 0, becomes the bisection of what
     * is left, so the iteration cannot leave the root's interval. Without
     * a bracket it is plain Newton from @p x, and a slope <= 0 jumps to
     * the middle of [@p lower, @p upper]. It stops when a step is at most
     * @p tolerance (1 + |x|), or after @p max_iterations steps.
     */
    template <typename Function>
    NewtonResult
    safeguarded_newton(const Function    &f,
                       double             x,
                       double             lower,
                       double             upper,
                       const bool         bracketed,
                       const double       tolerance,
                       const unsigned int max_iterations)
    {
      NewtonResult result;
      for (unsigned int it = 0; it < max_iterations; ++it)
        {
          double value = 0, slope = 0;
          f(x, value, slope);
          if (bracketed)
            {
              if (value < 0)
                lower = x;
              else
                upper = x;
            }
          double next = (slope > 0) ? x - value / slope : 0.5 * (lower + upper);
          if (bracketed && (next <= lower || next >= upper))
            next = 0.5 * (lower + upper);
          const double step = std::abs(next - x);
          x                 = next;
          if (step < tolerance * (1. + std::abs(x)))
            {
              result.converged = true;
              break;
            }
        }
      result.x = x;
      return result;
    }
  } // namespace geometry
} // namespace cycloid

#endif
