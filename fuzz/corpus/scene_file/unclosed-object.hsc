scene "unclosed" {
  object "a" sphere radius 5 mm at 0 mm, 0 mm, 0 mm {
    material "corduroy"
  object "b" box 10 mm x 10 mm x 10 mm at 0 mm, 0 mm, 0 mm {
    material "velvet" on top
    material "velvet" on top
  }
