; generatedF7800
;TYPE:External perimetew
;WIDTH:0.5
G1 X120 Y100 E1.0 F1200
G1 X120 Y120 E2.0
G1 X100 Y120 E3.0
G1 X100 Y100 E4.0
G10 ; retract
;LAYER_CHANGE
;Z:1.45
;HEIGHT:0.15
G1 Z.45 F7800
G1 X100 Y100
G11 ; unretract
;TYPE:External perimeter
;WIDTH:0.45
G1 X120 Y100 E4.6 F1800
G1 X120 Y120 E5.2
G10 ; retract
M107
; 1.245
; temperature = 210
; trave_slpeed = 150
; use_firm= 0
; complete_objects = 0
; spiral_vase = 0
; SuperSlicer_config = end
