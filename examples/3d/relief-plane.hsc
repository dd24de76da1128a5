# Textures felt as relief (Minsky 1995, 7.7.2: lateral- and normal-force textures combined): the
# material's texture carved into the surface along its normal, felt through the contact's spring.
# On the floor corduroy's ribs stand 0.5 mm above its grooves and still push sideways; on the
# block a broad grating is felt through its relief alone (`only`).
scene "relief plane" {
  object "floor" plane 160 mm x 160 mm at 0 mm, 0 mm, 0 mm {
    material "corduroy"
    stiffness 1000 N/m
    texture relief 0.5 mm
  }
  object "block" box 60 mm x 20 mm x 60 mm at 130 mm, 10 mm, 0 mm {
    material "grating period 6 mm smoothing 0.6 mm; roughness 0.4"
    stiffness 1000 N/m
    friction 0.3 0.2
    texture relief 0.5 mm only
  }
}
