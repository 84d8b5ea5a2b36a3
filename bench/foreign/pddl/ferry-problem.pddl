; 3 places, 3 cars, each car to another place.
(define (problem ferry-3-3)
  (:domain ferry)
  (:objects p1 p2 p3 - place c1 c2 c3 - car)
  (:init (not-eq p1 p2) (not-eq p1 p3) (not-eq p2 p1) (not-eq p2 p3) (not-eq p3 p1) (not-eq p3 p2)
         (empty-ferry) (at-ferry p1) (at c1 p1) (at c2 p2) (at c3 p3))
  (:goal (and (at c1 p2) (at c2 p3) (at c3 p1))))
