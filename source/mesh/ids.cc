#include <cycloid/mesh/ids.h>

namespace cycloid
{
  namespace mesh
  {
    std::string
    ids::boundary_name(const dealii::types::boundary_id b)
    {
      switch (b)
        {
          case flank:
            return "tooth flank";
          case bore:
            return "bore";
          case crank_hole:
            return "crank holes";
          case pin_surface:
            return "pin surface";
          case housing_seat:
            return "housing seat";
          case housing_outer:
            return "housing outer";
          case housing_inner:
            return "housing inner";
          case disc_axial:
            return "disc axial faces";
          case pin_axial:
            return "pin end faces";
          case housing_axial:
            return "housing axial faces";
          default:
            return "boundary " + std::to_string(b);
        }
    }



    std::string
    ids::body_name(const dealii::types::material_id m)
    {
      if (is_disc(m))
        return "disc " + std::to_string(m);
      if (m == housing)
        return "housing";
      if (is_pin(m))
        return "pin " + std::to_string(pin_index(m));
      return "body " + std::to_string(m);
    }
  } // namespace mesh
} // namespace cycloid
