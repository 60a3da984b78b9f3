#include <cycloid/postprocess/columns.h>
#include <cycloid/results/error_estimate.h>

#include <cmath>

namespace cycloid
{
  namespace postprocess
  {
    namespace u = results::units;

    // (+ 0. turns a negative zero, e.g. of a zero-torque limit, into 0 in
    // the CSV.)

    const std::vector<Column<StiffnessRow>> &
    stiffness_columns()
    {
      using R                                     = StiffnessRow;
      static const std::vector<Column<R>> columns = {
        {"step", [](auto &o, const R &r) { o << r.state.step; }},
        {"crank_deg",
         [](auto &o, const R &r) { o << r.state.crank * u::deg_per_rad; }},
        {"torque_Nm", [](auto &o, const R &r) { o << r.state.torque + 0.; }},
        {"rotation_rad",
         [](auto &o, const R &r) { o << r.state.rotation + 0.; }},
        {"K_secant_Nm_per_rad",
         [](auto &o, const R &r) { o << r.state.k_secant() + 0.; }},
        {"K_tangent_Nm_per_rad",
         [](auto &o, const R &r) { o << r.state.k_tangent; }},
        {"pins_in_contact",
         [](auto &o, const R &r) { o << r.state.pins_in_contact(); }},
        {"active_set_iterations",
         [](auto &o, const R &r) { o << r.state.iterations; }},
        {"dofs", [](auto &o, const R &r) { o << r.state.dofs; }},
        {"wall_s", [](auto &o, const R &r) { o << r.state.wall_s; }},
        {"K_secant_Nm_per_arcmin",
         [](auto &o, const R &r) {
           o << r.state.k_secant() * u::rad_per_arcmin;
         }},
        {"K_tangent_Nm_per_arcmin",
         [](auto &o, const R &r) {
           o << r.state.k_tangent * u::rad_per_arcmin;
         }},
        {"takeup_rad", [](auto &o, const R &r) { o << r.state.takeup + 0.; }},
        {"K_secant_elastic_Nm_per_rad",
         [](auto &o, const R &r) { o << r.state.k_secant_elastic(); }},
        {"reaction_torque_Nm",
         [](auto &o, const R &r) { o << r.state.reaction_torque; }},
        {"max_pin_force_N",
         [](auto &o, const R &r) { o << r.state.max_pin_force(); }},
        {"linear_iterations",
         [](auto &o, const R &r) { o << r.state.linear_iterations; }},
        {"peak_memory_MB",
         [](auto &o, const R &r) { o << r.state.peak_memory_MB; }},
        {"transmission_error_arcsec",
         [](auto &o, const R &r) {
           o << r.state.rotation * u::arcsec_per_rad + 0.;
         }},
        {"preconditioner_setups",
         [](auto &o, const R &r) { o << r.state.preconditioner_setups; }},
        {"K_secant_error",
         [](auto &o, const R &r) { o << r.state.error.k_secant; }},
        {"K_tangent_error",
         [](auto &o, const R &r) { o << r.state.error.k_tangent; }},
        {"max_pin_force_error",
         [](auto &o, const R &r) { o << r.state.error.max_pin_force; }},
        {"mesh_warning", [](auto &o, const R &r) { o << (r.flagged ? 1 : 0); }},
        {"hertz_nodes",
         [](auto &o, const R &r) { o << r.max_pin_hertz_nodes; }},
        {"resolution_error",
         [](auto &o, const R &r) { o << results::resolution_error(r.state); }},
        {"bulk_error", [](auto &o, const R &r) { o << r.state.error.bulk; }},
        // The state's highest peak contact pressure over all pins, and
        // where: it need not be on the most loaded pin.
        {"max_contact_pressure_MPa",
         [](auto &o, const R &r) {
           const auto p = r.state.highest_pressure_pin();
           o << (p == r.state.pins.end() ? 0. : p->max_pressure);
         }},
        {"max_pressure_disc",
         [](auto &o, const R &r) {
           const auto p = r.state.highest_pressure_pin();
           o << (p == r.state.pins.end() ? -1 : int(p->disc));
         }},
        {"max_pressure_pin", [](auto &o, const R &r) {
           const auto p = r.state.highest_pressure_pin();
           o << (p == r.state.pins.end() ? -1 : int(p->pin));
         }}};
      return columns;
    }



    const std::vector<Column<PinRow>> &
    pin_force_columns()
    {
      using R                                     = PinRow;
      static const std::vector<Column<R>> columns = {
        {"step", [](auto &o, const R &r) { o << r.state.step; }},
        {"crank_deg",
         [](auto &o, const R &r) { o << r.state.crank * u::deg_per_rad; }},
        {"disc", [](auto &o, const R &r) { o << r.pin.disc; }},
        {"pin", [](auto &o, const R &r) { o << r.pin.pin; }},
        {"Fx_N", [](auto &o, const R &r) { o << r.pin.fx + 0.; }},
        {"Fy_N", [](auto &o, const R &r) { o << r.pin.fy + 0.; }},
        {"Fn_N", [](auto &o, const R &r) { o << r.pin.fn; }},
        {"arm_mm", [](auto &o, const R &r) { o << r.pin.arm; }},
        {"clearance_um",
         [](auto &o, const R &r) { o << r.pin.clearance * u::um_per_mm; }},
        {"phase_deg",
         [](auto &o, const R &r) { o << r.pin.phase * u::deg_per_rad; }},
        {"approach_um",
         [](auto &o, const R &r) { o << r.pin.approach * u::um_per_mm; }},
        {"pair_stiffness_N_per_mm",
         [](auto &o, const R &r) { o << r.pin.pair_stiffness; }},
        {"contact_x_mm",
         [](auto &o, const R &r) { o << r.pin.contact_point[0]; }},
        {"contact_y_mm",
         [](auto &o, const R &r) { o << r.pin.contact_point[1]; }},
        {"contact_halfwidth_um",
         [](auto &o, const R &r) {
           o << r.pin.contact_halfwidth * u::um_per_mm;
         }},
        {"hertz_halfwidth_um",
         [](auto &o, const R &r) {
           o << r.pin.hertz_halfwidth * u::um_per_mm;
         }},
        {"max_contact_pressure_MPa",
         [](auto &o, const R &r) { o << r.pin.max_pressure; }},
        {"hertz_pressure_MPa",
         [](auto &o, const R &r) { o << r.pin.hertz_pressure; }},
        {"max_shear_stress_MPa",
         [](auto &o, const R &r) { o << r.pin.max_shear_stress; }},
        {"max_shear_depth_um",
         [](auto &o, const R &r) {
           o << r.pin.max_shear_depth * u::um_per_mm;
         }},
        {"Fn_error_N", [](auto &o, const R &r) { o << r.pin.fn_error; }},
        {"active_nodes", [](auto &o, const R &r) { o << r.pin.active_nodes; }},
        {"hertz_nodes", [](auto &o, const R &r) { o << r.pin.hertz_nodes; }}};
      return columns;
    }



    const std::vector<Column<BearingRow>> &
    bearing_columns()
    {
      using R                                     = BearingRow;
      static const std::vector<Column<R>> columns = {
        {"step", [](auto &o, const R &r) { o << r.state.step; }},
        {"crank_deg",
         [](auto &o, const R &r) { o << r.state.crank * u::deg_per_rad; }},
        {"disc", [](auto &o, const R &r) { o << r.bearing.disc; }},
        {"crank", [](auto &o, const R &r) { o << r.bearing.crank; }},
        {"Fx_N", [](auto &o, const R &r) { o << r.bearing.fx + 0.; }},
        {"Fy_N", [](auto &o, const R &r) { o << r.bearing.fy + 0.; }},
        {"F_N",
         [](auto &o, const R &r) {
           o << std::hypot(r.bearing.fx, r.bearing.fy);
         }},
        {"deflection_um",
         [](auto &o, const R &r) { o << r.bearing.deflection * u::um_per_mm; }},
        {"rollers_loaded",
         [](auto &o, const R &r) { o << r.bearing.rollers_loaded; }},
        {"max_roller_load_N",
         [](auto &o, const R &r) { o << r.bearing.max_roller_load; }}};
      return columns;
    }



    const std::vector<Column<results::StageState>> &
    breakdown_columns()
    {
      using R                                     = results::StageState;
      static const std::vector<Column<R>> columns = {
        {"step", [](auto &o, const R &s) { o << s.step; }},
        {"crank_deg",
         [](auto &o, const R &s) { o << s.crank * u::deg_per_rad; }},
        {"torque_Nm", [](auto &o, const R &s) { o << s.torque; }},
        {"total_rad", [](auto &o, const R &s) { o << s.rotation; }},
        {"contacts_rad",
         [](auto &o, const R &s) { o << s.breakdown.contacts; }},
        {"bodies_rad", [](auto &o, const R &s) { o << s.breakdown.bodies; }},
        {"bearings_rad",
         [](auto &o, const R &s) { o << s.breakdown.bearings; }}};
      return columns;
    }



    const std::vector<Column<EnergyRow>> &
    energy_columns()
    {
      using R                                     = EnergyRow;
      static const std::vector<Column<R>> columns = {
        {"step", [](auto &o, const R &r) { o << r.energy.step; }},
        {"time_s", [](auto &o, const R &r) { o << r.energy.time_s; }},
        {"kinetic_J", [](auto &o, const R &r) { o << r.energy.kinetic; }},
        {"elastic_J", [](auto &o, const R &r) { o << r.energy.elastic; }},
        {"external_work_J",
         [](auto &o, const R &r) { o << r.energy.external; }},
        {"active_set_iterations",
         [](auto &o, const R &r) { o << r.state.iterations; }},
        {"crank_deg",
         [](auto &o, const R &r) { o << r.state.crank * u::deg_per_rad; }},
        {"torque_Nm", [](auto &o, const R &r) { o << r.state.torque; }},
        {"rotation_rad", [](auto &o, const R &r) { o << r.state.rotation; }},
        {"bore_work_J", [](auto &o, const R &r) { o << r.energy.bore_work; }},
        {"contact_work_J",
         [](auto &o, const R &r) { o << r.energy.contact_work; }},
        {"dissipated_J", [](auto &o, const R &r) { o << r.energy.dissipated; }},
        {"balance_error_J", [](auto &o, const R &r) { o << r.energy.balance; }},
        {"relative_balance_error",
         [](auto &o, const R &r) { o << r.energy.relative_balance; }},
        {"max_penetration_um",
         [](auto &o, const R &r) { o << r.energy.max_penetration_um; }},
        {"wall_s", [](auto &o, const R &r) { o << r.state.wall_s; }},
        {"angular_momentum_Nms",
         [](auto &o, const R &r) { o << r.energy.angular_momentum; }}};
      return columns;
    }
  } // namespace postprocess
} // namespace cycloid
