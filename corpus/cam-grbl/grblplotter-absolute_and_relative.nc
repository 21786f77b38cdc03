(Test mix of abs and rel)
G0 X10 Y10 Z2

G91
G0 X-5 Y-5
G1 Z-5
Y10
X10
Y-10
X-10
Z5
G90

G0 X30 Y10 Z2

G91
G0 X-5 Y-5
G1 Z-5
Y10
X10
Y-10
X-10
Z5
G90

G0 X50 Y10 Z2

G91
G0 X-5 Y-5
G1 Z-5
Y10
X10
Y-10
X-10
Z5
G90

M30

