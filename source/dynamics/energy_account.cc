#include <deal.II/base/exceptions.h>

#include <cycloid/dynamics/energy_account.h>

#include <algorithm>
#include <cmath>
#include <istream>
#include <ostream>

namespace cycloid
{
  namespace dynamics
  {
    EnergyAccount::EnergyAccount(const double       max_error,
                                 const std::string &scheme_name,
                                 const bool         crank_turns)
      : max_error(max_error)
      , scheme_name(scheme_name)
      , crank_turns(crank_turns)
    {}



    results::EnergyState
    EnergyAccount::account(const StepReport  &report,
                           const double       J,
                           const unsigned int step,
                           const double       time)
    {
      results::EnergyState e;
      e.step         = step;
      e.time_s       = time;
      e.kinetic      = report.kinetic * J;
      e.elastic      = report.elastic * J;
      e.bore_work    = report.bore_work * J;
      e.contact_work = report.contact_work * J;
      e.dissipated   = report.dissipated * J;
      e.external     = (report.bore_work + report.contact_work) * J;
      const double total =
        (report.kinetic + report.elastic + report.dissipated) * J;
      e.balance = total - e.external - initial_energy;
      // Relative to the largest energy level reached so far (the net work
      // falls while the stage swings back, so it cannot be the scale).
      energy_scale = std::max({energy_scale, std::abs(e.external), total});
      e.relative_balance   = e.balance / std::max(energy_scale, 1e-300);
      e.max_penetration_um = report.max_penetration * 1e3;
      return e;
    }



    void
    EnergyAccount::check(const results::EnergyState &e,
                         const std::string          &label,
                         dealii::ConditionalOStream &out)
    {
      const double relative = e.relative_balance;
      if (std::abs(relative) > 0.05 && !warned && energy_scale > 0)
        {
          warned = true;
          out << "  warning: energy balance error " << 100. * relative
              << " % of the largest energy level at step " << e.step
              << (crank_turns ?
                    " (with the crank turning this includes the time "
                    "discretisation of the moving contacts; a smaller Time "
                    "step reduces it, see doc/stability.md)" :
                    "")
              << std::endl;
        }
      AssertThrow(std::abs(relative) <= max_error || energy_scale <= 0,
                  dealii::ExcMessage(
                    "transient: the energy balance error reached " +
                    std::to_string(100. * relative) +
                    " % of the largest energy level at " + label +
                    " (Transient/Maximum energy error " +
                    std::to_string(100. * max_error) +
                    " %): the time integration does not keep the energy "
                    "balance (Scheme = " +
                    scheme_name +
                    "). Plain Newmark chatters at contact: use Scheme = "
                    "contact-stabilised or generalized-alpha; with the "
                    "crank turning, a smaller Time step reduces the "
                    "moving-contact share. The rows written so far are "
                    "valid."));
    }



    void
    EnergyAccount::checkpoint(CheckpointArchive &ar)
    {
      ar.value(initial_energy);
      ar.value(energy_scale);
    }
  } // namespace dynamics
} // namespace cycloid
