// table: 44x44x3 top at z 27 on four 5x5 legs
translate([0,0,27]) cube([44,44,3]);
for (x=[0,39]) for (y=[0,39]) translate([x,y,0]) cube([5,5,27]);
