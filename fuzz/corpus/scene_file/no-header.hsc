object "o" sphere radius 5 mm at 0 mm, 0 mm, 0 mm
