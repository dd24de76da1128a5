scene "every form" {
  object "room" box 2 m x 2.5 m x 3 m inside at 0 m, 1.25 m, 0 m {
    material "window-glass"; material "velvet" on bottom
    material "corduroy" on front
    damping 2 N*s/m
    stiffness 0.8 N/mm
    friction 0.4
    texture size 40 mm x 20 mm
  }
  object "wall" plane 1 in x 2 in facing front at -10 cm, 0 mm, -5 mm
  object "one line" sphere radius 1 cm at 1e1 mm, 0 mm, 0 mm { material "roughness 0.4; grating period 2 mm"; texture size 5 mm }
  object "stone" box 30 mm x 30 mm x 30 mm at 0 mm, 15 mm, 60 mm {
    material "../corduroy.hmat" on left
    material "a10p25" on right
    material "gravel" on back
  }
}
