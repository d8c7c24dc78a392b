// The CSG of scenes/csg-pov.yaml for POV-Ray 3.7 (bench/povray-shapes.sh csg): the camera, light,
// plane and finish of bench/shapes.pov with opaque versions of scenes/csg.yaml's solids — a
// rounded cube with three holes, a lens, a box with a groove, merged and united spheres, a
// cylinder notched by an inverse box, and an egg.
#version 3.7;

global_settings {
  assumed_gamma 1.0          // colours are linear; run with File_Gamma=1.0 to store raw values
  max_trace_level 8
  ambient_light rgb 1
}

camera {
  perspective
  location <0, 0.8, 2.2>
  look_at  <0, 0.25, 0>
  right   -x*image_width/image_height
  angle 50
}

light_source { <1, 1.5, 1> color rgb <1,1,1> }

#declare F = finish { ambient 0.1 diffuse 0.7 specular 0.6 roughness 0.01 }

plane { <0,1,0>, 0 pigment { color rgb 0.3 } finish { F } }

// (box ∩ sphere) − three cylinders, turned 45° about y (the same either way round).
difference {
  intersection {
    box { <-0.18, -0.18, -0.18>, <0.18, 0.18, 0.18> }
    sphere { <0, 0, 0>, 0.24 }
  }
  cylinder { <-0.25, 0, 0>, <0.25, 0, 0>, 0.1 }
  cylinder { <0, -0.25, 0>, <0, 0.25, 0>, 0.1 }
  cylinder { <0, 0, -0.25>, <0, 0, 0.25>, 0.1 }
  rotate <0, 45, 0>
  translate <-0.5, 0.18, -0.15>
  pigment { color rgb <0.8,0.2,0.2> } finish { F }
}
// A lens on its rim: two spheres intersected.
intersection {
  sphere { <-0.2, 0.25, -0.65>, 0.35 }
  sphere { < 0.2, 0.25, -0.35>, 0.35 }
  pigment { color rgb <0.2,0.4,0.5> } finish { F }
}
// A box with a groove: minus a torus whose tube cuts its top, and a hole.
difference {
  box { <0.25, 0, -0.05>, <0.65, 0.2, 0.25> }
  torus { 0.1, 0.04 translate <0.45, 0.2, 0.1> }
  cylinder { <0.45, 0.1, 0.1>, <0.45, 0.25, 0.1>, 0.05 }
  pigment { color rgb <0.5,0.5,0.1> } finish { F }
}
merge {
  sphere { <-0.25, 0.1, 0.5>, 0.1 }
  sphere { <-0.12, 0.1, 0.5>, 0.1 }
  pigment { color rgb <0,0,1> } finish { F }
}
union {
  sphere { <0.12, 0.1, 0.5>, 0.1 }
  sphere { <0.25, 0.1, 0.5>, 0.1 }
  pigment { color rgb <0,1,0> } finish { F }
}
// A cylinder notched by an inverse box: an intersection that is a difference.
intersection {
  cylinder { <0.7, 0, 0.4>, <0.7, 0.3, 0.4>, 0.12 }
  box { <0.55, 0.1, 0.42>, <0.85, 0.2, 0.6> inverse }
  pigment { color rgb <0.2,0.6,0.6> } finish { F }
}
// An egg: a sphere scaled unevenly.
sphere { <0, 0, 0>, 0.08 scale <1, 1.4, 1> translate <-0.75, 0.112, 0.4>
  pigment { color rgb <0.8,0.7,0.1> } finish { F } }
