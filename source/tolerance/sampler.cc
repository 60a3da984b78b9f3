#include <deal.II/base/exceptions.h>

#include <deal.II/base/numbers.h>

#include <cycloid/tolerance/sampler.h>

#include <cmath>
#include <fstream>
#include <limits>

namespace cycloid
{
  namespace tolerance
  {
    namespace
    {
      /**
       * SplitMix64 (Steele, Lea, Flood 2014): a small generator of full
       * period whose stream from a seed is fixed by its few lines, unlike
       * std::normal_distribution's, which each library implements its own
       * way.
       */
      class Generator
      {
      public:
        explicit Generator(const std::uint64_t seed)
          : state(seed)
        {}

        /** SplitMix64's output function: 64 well-mixed bits of @p z. */
        static std::uint64_t
        mix(std::uint64_t z)
        {
          z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
          z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
          return z ^ (z >> 31);
        }

        /** Uniform in (0, 1]. */
        double
        uniform()
        {
          return ((mix(state += 0x9e3779b97f4a7c15ULL) >> 11) + 1.) * 0x1.0p-53;
        }

        /** Standard normal (Box-Muller, the cosine branch). */
        double
        normal()
        {
          const double u1 = uniform(), u2 = uniform();
          return std::sqrt(-2. * std::log(u1)) *
                 std::cos(2. * dealii::numbers::PI * u2);
        }

      private:
        std::uint64_t state;
      };

      /** A deviation in a +- @p band: normal with the band as 3 sigma, or
       * uniform. Draws two numbers either way. */
      double
      in_band(Generator &g, const double band, const bool normal)
      {
        const double z = g.normal();
        // The uniform variant reuses the normal's first uniform through
        // the normal CDF, so both variants consume the same numbers.
        return normal ? band / 3. * z : band * std::erf(z / std::sqrt(2.));
      }
    } // namespace



    std::string
    band_name(const unsigned int b)
    {
      static const char *names[n_bands] = {"Pin position tolerance",
                                           "Pin radius tolerance",
                                           "Eccentricity tolerance",
                                           "Disc angle tolerance",
                                           "Profile tolerance"};
      AssertIndexRange(b, n_bands);
      return names[b];
    }



    double
    band_width(const ToleranceParameters &p, const unsigned int b)
    {
      const double widths[n_bands] = {
        p.pin_position, p.pin_radius, p.eccentricity, p.disc_angle, p.profile};
      AssertIndexRange(b, n_bands);
      return widths[b];
    }



    StageDeviations
    StageDeviations::zero(const unsigned int n_pins)
    {
      StageDeviations d;
      d.pins.resize(n_pins);
      for (unsigned int j = 0; j < n_pins; ++j)
        d.pins[j].pin = j;
      d.discs.resize(2);
      for (unsigned int k = 0; k < 2; ++k)
        d.discs[k].disc = k;
      return d;
    }



    StageDeviations
    StageDeviations::from_rows(
      const unsigned int                          n_pins,
      const std::vector<geometry::PinDeviation>  &pins,
      const std::vector<geometry::DiscDeviation> &discs)
    {
      StageDeviations d = zero(n_pins);
      for (const auto &p : pins)
        d.pins.at(p.pin) = p;
      for (const auto &q : discs)
        d.discs.at(q.disc) = q;
      return d;
    }



    void
    StageDeviations::write(const std::string &pin_file,
                           const std::string &disc_file) const
    {
      std::ofstream p(pin_file), q(disc_file);
      AssertThrow(p && q,
                  dealii::ExcMessage("cannot write " + pin_file + " or " +
                                     disc_file));
      p.precision(std::numeric_limits<double>::max_digits10);
      q.precision(std::numeric_limits<double>::max_digits10);
      p << "pin,radial_um,tangential_um,radius_um\n";
      for (const auto &d : pins)
        p << d.pin << ',' << d.radial_um << ',' << d.tangential_um << ','
          << d.radius_um << '\n';
      q << "disc,eccentricity_um,angle_arcmin,pin_circle_um,pin_radius_um\n";
      for (const auto &d : discs)
        q << d.disc << ',' << d.eccentricity_um << ',' << d.angle_arcmin << ','
          << d.pin_circle_um << ',' << d.pin_radius_um << '\n';
    }



    Sampler::Sampler(const ToleranceParameters &parameters,
                     const StageDeviations     &mean)
      : parameters(parameters)
      , mean(mean)
    {}



    BandMask
    Sampler::all_bands()
    {
      BandMask on;
      on.fill(true);
      return on;
    }



    StageDeviations
    Sampler::draw(const unsigned int s, const BandMask &on) const
    {
      StageDeviations d = mean;
      if (s == 0)
        return d;
      // The seed and the sample index, mixed into one 64-bit seed (a
      // second SplitMix64 step decorrelates neighbouring samples).
      Generator  g(Generator::mix((std::uint64_t(parameters.seed) << 32) ^ s));
      const bool normal =
        parameters.distribution == ToleranceParameters::Distribution::normal;
      const auto width = [&](const Band b) {
        return on[b] ? band_width(parameters, b) : 0.;
      };
      const double pi = dealii::numbers::PI;
      for (auto &p : d.pins)
        {
          // True position: a circle of diameter t about the nominal centre.
          const double t = width(pin_position_band);
          double       x = 0, y = 0;
          if (normal)
            {
              x = t / 6. * g.normal();
              y = t / 6. * g.normal();
            }
          else
            {
              const double r = 0.5 * t * std::sqrt(g.uniform());
              const double a = 2. * pi * g.uniform();
              g.uniform(), g.uniform(); // as many numbers as normal()
              x = r * std::cos(a);
              y = r * std::sin(a);
            }
          p.radial_um += x;
          p.tangential_um += y;
          p.radius_um += in_band(g, width(pin_radius_band), normal);
        }
      for (auto &q : d.discs)
        {
          q.eccentricity_um += in_band(g, width(eccentricity_band), normal);
          q.angle_arcmin += in_band(g, width(disc_angle_band), normal);
          q.pin_circle_um += in_band(g, width(profile_band), normal);
          q.pin_radius_um += in_band(g, width(profile_band), normal);
        }
      return d;
    }
  } // namespace tolerance
} // namespace cycloid
