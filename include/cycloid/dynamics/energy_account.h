#ifndef cycloid_dynamics_energy_account_h
#define cycloid_dynamics_energy_account_h

#include <deal.II/base/conditional_ostream.h>

#include <cycloid/dynamics/contact_dynamics.h>
#include <cycloid/results/energy_state.h>

#include <iosfwd>
#include <string>

namespace cycloid
{
  namespace dynamics
  {
    /**
     * @brief The energy balance of a transient run, step by step:
     * E_kin + E_el + D - W_load - W_contact - E_0 against the largest energy
     * level reached. It is the run's stability test: a scheme that chatters
     * at contact gains energy (plain Newmark) and its forces are then
     * wrong, so the account warns once and stops the run with a message
     * rather than let such numbers be written on.
     */
    class EnergyAccount
    {
    public:
      /** Stop above @p max_error (relative); @p scheme_name and
       * @p crank_turns make the messages specific. */
      EnergyAccount(const double       max_error,
                    const std::string &scheme_name,
                    const bool         crank_turns);

      /**
       * The energy row of step @p step at @p time [s] from the scheme's
       * totals @p report (N mm, per unit thickness in 2D) scaled by @p to_J
       * to J for the whole stage; updates the energy scale.
       */
      results::EnergyState
      account(const StepReport  &report,
              const double       to_J,
              const unsigned int step,
              const double       time);

      /** Warn (once, on @p out) above 5 %, throw naming @p label above the
       * limit. */
      void
      check(const results::EnergyState &row,
            const std::string          &label,
            dealii::ConditionalOStream &out);

      /** Write the account to a checkpoint or restore it from one. */
      void
      checkpoint(CheckpointArchive &ar);

    private:
      const double      max_error;
      const std::string scheme_name;
      const bool        crank_turns;
      /** E_0 [J] (the runs start at rest). */
      double initial_energy = 0;
      /** Largest of E_kin + E_el + D and |W| so far [J]. */
      double energy_scale = 0;
      bool   warned       = false;
    };
  } // namespace dynamics
} // namespace cycloid

#endif
