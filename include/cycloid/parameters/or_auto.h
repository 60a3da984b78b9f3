#ifndef cycloid_parameters_or_auto_h
#define cycloid_parameters_or_auto_h

#include <deal.II/base/patterns.h>

#include <memory>
#include <string>

namespace cycloid
{
  namespace parameters
  {
    /**
     * @brief The pattern of an entry whose default is `auto` (a value the
     * code derives from other entries) and that also takes any value of
     * another pattern, e.g. `Bore radius = auto` or `= 20`. deal.II has no
     * union of patterns; this one matches `auto` or what @p base matches, so
     * that a bad value is still rejected with its line by parse_input().
     */
    class OrAuto : public dealii::Patterns::PatternBase
    {
    public:
      /** Match `auto` or anything @p base matches. */
      explicit OrAuto(const dealii::Patterns::PatternBase &base);

      /** Whether @p test is `auto` or matches the base pattern. */
      bool
      match(const std::string &test) const override;

      /** "[auto or <base description>]". */
      std::string
      description(const OutputStyle style = Machine) const override;

      /** A copy. */
      std::unique_ptr<dealii::Patterns::PatternBase>
      clone() const override;

    private:
      std::unique_ptr<dealii::Patterns::PatternBase> base;
    };

    /** Whether the entry value @p value is `auto`. */
    inline bool
    is_auto(const std::string &value)
    {
      return value == "auto";
    }
  } // namespace parameters
} // namespace cycloid

#endif
