scene "units" {
  object "no unit" sphere radius 5 at 0 mm, 0 mm, 0 mm
  object "typo" sphere radius 5 mn at 0 mm, 0 mm, 0 mm
  object "force" sphere radius 5 N at 0 mm, 0 mm, 0 mm
  object "huge" sphere radius 1e300 m at 0 mm, 0 mm, 0 mm
  object "tiny" sphere radius 1 m at 1e-20 m, 0 mm, 0 mm
  object "contact" box 1 m x 1 m x 1 m at 0 mm, 0 mm, 0 mm {
    stiffness 800 N*s/m
    damping -1 N*s/m
    friction 0.5 N
    friction 1e20
    texture size 0 mm
  }
}
