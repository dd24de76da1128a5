scene "reliefs" {
  object "floor" plane 160 mm x 160 mm at 0 mm, 0 mm, 0 mm {
    material "corduroy"
    texture relief 0.5 mm
  }
  object "block" box 60 mm x 20 mm x 60 mm at 130 mm, 10 mm, 0 mm {
    material "grating period 6 mm smoothing 0.6 mm; roughness 0.4"
    texture size 40 mm x 20 mm
    texture relief 1 cm only
  }
  object "pebble" sphere radius 5 mm at 0 mm, 5 mm, 0 mm { material "sandpaper-p80"; texture relief 200 um only; friction 0.4 }
}
