* Hand-made infeasible MIQP.
*   min 0.5 x^2 + b   s.t. c1: x + b >= 2,  x in [0, 0.5], b binary
* x + b <= 1.5 < 2 whatever b is, so no point satisfies c1.
NAME infeasible
ROWS
 N obj
 G c1
COLUMNS
 x c1 1
 MARKER 'MARKER' 'INTORG'
 b obj 1 c1 1
 MARKER 'MARKER' 'INTEND'
RHS
 rhs c1 2
BOUNDS
 UP bnd x 0.5
 BV bnd b
QUADOBJ
 x x 1
ENDATA
