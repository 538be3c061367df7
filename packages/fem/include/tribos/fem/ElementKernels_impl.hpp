// ElementKernels implementation: to be written
