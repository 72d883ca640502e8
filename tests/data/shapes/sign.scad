// sign post: 8x8 post 35 tall with a 30 mm arm at z 25 and a hanging plate
cube([8,8,35]);
translate([8,0,25]) cube([30,8,4]);
translate([20,2,10]) cube([14,4,15]);
