// Image maps for POV-Ray 3.7 and strahl's importer (bench/povray-import.sh): one picture
// (scenes/textures/grid.png, 8 x 4 coloured cells) laid on the floor (planar, bilinear, turned
// onto the floor and scaled), wrapped around a sphere (spherical, bilinear, turned with it),
// around a cylinder (cylindrical, nearest) and onto a box (planar, once: the box lies inside the
// image's unit cube, so no point falls outside it). Transforms after the pigment move the picture
// with the object, as in POV-Ray.
#version 3.7;
global_settings { assumed_gamma 1.0 ambient_light rgb 1 }
camera { perspective location <0, 2.6, -6.5> look_at <0, 0.8, 0> right x*image_width/image_height angle 50 }
light_source { <-4, 6, -5> color rgb 0.9 }
light_source { <5, 4, -3> color rgb 0.3 }
#declare Grid = "../../scenes/textures/grid.png";
#declare F = finish { ambient 0.15 diffuse 0.7 specular 0.4 roughness 0.02 }
plane { y, 0
  pigment { image_map { png Grid interpolate 2 } scale <4, 2, 1> rotate x*90 }
  finish { ambient 0.15 diffuse 0.8 } }
sphere { 0, 1
  pigment { image_map { png Grid map_type 1 interpolate 2 } }
  finish { F }
  rotate y*35 translate <-1.5, 1, 0> }
cylinder { 0, y, 1
  pigment { image_map { png Grid map_type 2 } }
  finish { F }
  scale <0.6, 1.6, 0.6> translate <1.6, 0, 0.3> }
box { 0.001, 0.999
  pigment { image_map { png Grid once } }
  finish { F }
  translate <-0.5, 0, -0.5> scale <0.9, 0.6, 0.6> rotate y*-20 translate <0.1, 0, -1.6> }
