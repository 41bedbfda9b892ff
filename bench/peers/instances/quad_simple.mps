* Hand-made MIQP with a known optimum (free MPS, QUADOBJ, CPLEX convention).
*   min 0.5*(x - 1.5)^2 + 0.5*(y - 0.4)^2 + 0.2*b
*   s.t. c1: y + b >= 1
*        x integer in [0, 3], y continuous in [0, 10], b binary
* The constants 0.5*1.5^2 + 0.5*0.4^2 = 1.205 are left out of the file, so
*   MPS objective = 0.5 x^2 - 1.5 x + 0.5 y^2 - 0.4 y + 0.2 b.
* By hand: b = 0 forces y >= 1, best y = 1 costs 0.5*0.6^2 = 0.18;
*          b = 1 allows y = 0.4 at cost 0.2 > 0.18, so b = 0, y = 1.
*          x = 1 or x = 2 (tie), each costing 0.5*0.5^2 = 0.125.
*   optimum: MPS objective -0.9, full objective -0.9 + 1.205 = 0.305.
NAME quad_simple
ROWS
 N obj
 G c1
COLUMNS
 M1 'MARKER' 'INTORG'
 x obj -1.5
 M1 'MARKER' 'INTEND'
 y obj -0.4 c1 1
 M2 'MARKER' 'INTORG'
 b obj 0.2 c1 1
 M2 'MARKER' 'INTEND'
RHS
 rhs c1 1
BOUNDS
 UP bnd x 3
 UP bnd y 10
 BV bnd b
QUADOBJ
 x x 1
 y y 1
ENDATA
