#include <cycloid/parameters/or_auto.h>

namespace cycloid
{
  namespace parameters
  {
    OrAuto::OrAuto(const dealii::Patterns::PatternBase &base)
      : base(base.clone())
    {}



    bool
    OrAuto::match(const std::string &test) const
    {
      return is_auto(test) || base->match(test);
    }



    std::string
    OrAuto::description(const OutputStyle style) const
    {
      // Not "[Double ...]": deal.II's pattern_factory() would read the
      // description back as a plain Double and reject "auto".
      return "[auto or " + base->description(style) + "]";
    }



    std::unique_ptr<dealii::Patterns::PatternBase>
    OrAuto::clone() const
    {
      return std::make_unique<OrAuto>(*base);
    }
  } // namespace parameters
} // namespace cycloid
