#ifndef cycloid_results_energy_state_h
#define cycloid_results_energy_state_h

namespace cycloid
{
  namespace results
  {
    /**
     * @brief The energy account of a time step (transient runs), one row
     * of `energy.csv`: energies and works for the whole tooth width [J],
     * accumulated from t = 0. Beside StageState, which holds the step's
     * forces, so that the dynamics layer fills it without the report.
     */
    struct EnergyState
    {
      unsigned int step         = 0; ///< Time step index.
      double       time_s       = 0; ///< Time at the end of the step [s].
      double       kinetic      = 0; ///< Kinetic energy [J].
      double       elastic      = 0; ///< Elastic energy [J].
      double       external     = 0; ///< load surface + moving obstacles
      double       bore_work    = 0; ///< Work of the load surface [J].
      double       contact_work = 0; ///< Work of the moving obstacles [J].
      double       dissipated   = 0; ///< Rayleigh damping dissipation [J].
      /** E_kin + E_el + D - W - E_0 [J]. */
      double balance = 0;
      /** balance over the largest energy level reached [-]. */
      double relative_balance = 0;
      /** Largest penetration of a contact node [um]. */
      double max_penetration_um = 0;
      /** Angular momentum of the discs about their centres [N m s]. */
      double angular_momentum = 0;
    };
  } // namespace results
} // namespace cycloid

#endif
