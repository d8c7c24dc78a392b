// The solids of scenes/shapes-pov.yaml for POV-Ray 3.7 (bench/povray-shapes.sh): the lecture's
// camera, light, plane and finish (as ../shared/bench/lecture.pov) with a torus, a box, a
// cylinder, a cone and an isosurface where its spheres were.
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

torus { 0.22, 0.08 translate <0.05, 0.08, 0> pigment { color rgb <0.8,0.2,0.2> } finish { F } }
box { <0.3, 0, 0>, <0.5, 0.2, 0.2> pigment { color rgb <0,1,0> } finish { F } }
cylinder { <-0.35, 0, -0.15>, <-0.35, 0.45, -0.15>, 0.2 pigment { color rgb <0.5,0.5,0.1> } finish { F } }
cone { <-0.35, 0, 0.3>, 0.15, <-0.35, 0.3, 0.3>, 0 pigment { color rgb <0,0,1> } finish { F } }
isosurface {
  function { sqrt(pow(x - 0.15, 2) + pow(y - 0.6, 2) + pow(z + 1, 2)) - 0.55 + 0.03*sin(20*y) }
  contained_by { sphere { <0.15, 0.6, -1>, 0.65 } }
  max_gradient 1.7
  accuracy 0.0001
  pigment { color rgb <0.2,0.4,0.5> } finish { F }
}
