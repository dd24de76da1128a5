scene "s" {
  object "a" sphear radius 5 mm at 0 mm, 0 mm, 0 mm {
    material "x" on top
    stifness 800 N/m
  }
  object "b" sphere radius 5 mm at 0 mm, 0 mm, 0 mm {
    friction 0.3 0.5
    material "corduroy"
    damping 2 N*s/m extra
    stiffness 800 N/m
    stiffness 900 N/m
  }
  object "c" box 1 m x 1 m x 1 m at 0 mm, 0 mm, 0 mm { material "a" on up; friction 0.5 }
  object "d" sphere radius -1 mm at 0 mm, 0 mm, 0 mm {
    material "a" on top
    frction 0.5
  }
  object "b" plane 1 m x 1 m inside at 0 mm, 0 mm, 0 mm
  material "stray"
}
