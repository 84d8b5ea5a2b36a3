; 4 floors, 3 passengers (IPC 2000 miconic s3-x sizes).
(define (problem miconic-4-3)
  (:domain miconic)
  (:objects f0 f1 f2 f3 - floor p0 p1 p2 - passenger)
  (:init (above f0 f1) (above f0 f2) (above f0 f3) (above f1 f2) (above f1 f3) (above f2 f3)
         (origin p0 f3) (destin p0 f0) (origin p1 f1) (destin p1 f3) (origin p2 f2) (destin p2 f1)
         (lift-at f0))
  (:goal (and (served p0) (served p1) (served p2))))
