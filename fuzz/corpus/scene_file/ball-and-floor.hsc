# A textured ball above a floor.
scene "ball and floor" {
  object "ball" sphere radius 50 mm at 0 mm, 60 mm, 0 mm {
    material "corduroy"
    stiffness 800 N/m
    friction 0.5 0.3
  }
  object "floor" plane 300 mm x 300 mm at 0 mm, 0 mm, 0 mm {
    material "sandpaper-p80"
  }
  object "crate" box 80 mm x 40 mm x 80 mm at 100 mm, 20 mm, 0 mm {
    material "silk-satin"
    material "gravel" on top
  }
}
