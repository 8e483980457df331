!
!     sffcal's addition to CalculiX 2.20 (scripts/build_calculix.sh
!     links it into ccx_sffcal; not part of CalculiX).
!
!     umat_abaqus.f keeps only (D + D^T)/2 of a user material's DDSDDE
!     D, and the models' tangents are far from symmetric: Newton then
!     loses its quadratic rate and diverges on rough-platen meshes
!     (docs/fe.md, "CalculiX"). This routine gives element nelem's
!     share of the rest,
!
!        s = K_a = sum over the points of B^T D_a B |J| w,
!        D_a = (D - D^T)/2,
!
!     which mafillsmas.f (patched) adds to ccx's unsymmetric matrix
!     (nasym = 1) as it adds the contact elements': the same handling
!     of boundary conditions and equations. D_a comes from the UMAT's
!     table (model/src/umat_tangent_table.h; engineering shear, Abaqus
!     order 11 22 33 12 13 23). B is the derivative of the strain by
!     the nodal displacements, with engineering shear: B = sym(F^T
!     grad_0 N) of the Green-Lagrange strain in a step with NLGEOM (F
!     from the displacements), the small strain otherwise (F = I).
!
!     Elements: C3D8, C3D8I, C3D20 and C3D20R, at ccx's own points
!     (gauss.f) with its own shape functions; nope = their nodes. Other
!     elements and those with a local orientation keep the symmetric
!     tangent (said once on stdout): nope = 0, as for an element
!     without sffcal's material.
!
      subroutine sffcal_e_c3d_unsym(co,kon,ipkon,lakonl,nelem,vold,mi,
     &  iperturb,ielorien,norien,s,nope)
!
      implicit none
!
      character*8 lakonl
!
      integer kon(*),ipkon(*),nelem,mi(*),iperturb(*),
     &  ielorien(mi(3),*),norien,nope,indexe,mint3d,kk,i,j,k,m,jj,ll,
     &  found,iflag,said_type,said_orientation
!
      real*8 co(3,*),vold(0:mi(2),*),s(60,60),xl(3,23),shp(4,23),
     &  u(3,23),xsj,xi,et,ze,weight,da(6,6),f(3,3),b(6,60),db(6,60),wj
!
      save said_type,said_orientation
      data said_type /0/
      data said_orientation /0/
!
      include "gauss.f"
!
      nope=0
      call sffcal_umat_has_unsymmetric_part(nelem,found)
      if(found.eq.0) return
!
      if(lakonl(7:8).ne.'  ') then
        nope=0
      elseif(lakonl(1:5).eq.'C3D8 ') then
        nope=8
        mint3d=8
      elseif(lakonl(1:5).eq.'C3D8I') then
        nope=11
        mint3d=8
      elseif(lakonl(1:6).eq.'C3D20R') then
        nope=20
        mint3d=8
      elseif(lakonl(1:6).eq.'C3D20 ') then
        nope=20
        mint3d=27
      endif
      if(nope.eq.0) then
        if(said_type.eq.0) then
          write(*,*) '*WARNING in sffcal_e_c3d_unsym: element ',
     &      nelem,' (',lakonl,') keeps the symmetric part of its',
     &      ' user material''s tangent: ccx_sffcal adds the rest',
     &      ' to C3D8, C3D8I, C3D20 and C3D20R only'
          said_type=1
        endif
        return
      endif
      if(norien.gt.0) then
        if(ielorien(1,nelem).gt.0) then
          if(said_orientation.eq.0) then
            write(*,*) '*WARNING in sffcal_e_c3d_unsym: element ',
     &        nelem,' has a local orientation and keeps the',
     &        ' symmetric part of its user material''s tangent'
            said_orientation=1
          endif
          nope=0
          return
        endif
      endif
!
      indexe=ipkon(nelem)
      do i=1,nope
        do j=1,3
          xl(j,i)=co(j,kon(indexe+i))
          if(iperturb(2).eq.1) then
            u(j,i)=vold(j,kon(indexe+i))
          else
            u(j,i)=0.d0
          endif
        enddo
      enddo
!
      do jj=1,3*nope
        do ll=1,3*nope
          s(jj,ll)=0.d0
        enddo
      enddo
!
      iflag=3
      do kk=1,mint3d
        call sffcal_umat_unsymmetric_part(nelem,kk,da,found)
        if(found.eq.0) cycle
        if(mint3d.eq.8) then
          xi=gauss3d2(1,kk)
          et=gauss3d2(2,kk)
          ze=gauss3d2(3,kk)
          weight=weight3d2(kk)
        else
          xi=gauss3d3(1,kk)
          et=gauss3d3(2,kk)
          ze=gauss3d3(3,kk)
          weight=weight3d3(kk)
        endif
        if(nope.eq.11) then
          call shape8hu(xi,et,ze,xl,xsj,shp,iflag)
        elseif(nope.eq.20) then
          call shape20h(xi,et,ze,xl,xsj,shp,iflag)
        else
          call shape8h(xi,et,ze,xl,xsj,shp,iflag)
        endif
!
!       F = I + sum_i u_i (x) grad_0 N_i
!
        do k=1,3
          do m=1,3
            if(k.eq.m) then
              f(k,m)=1.d0
            else
              f(k,m)=0.d0
            endif
            do i=1,nope
              f(k,m)=f(k,m)+u(k,i)*shp(m,i)
            enddo
          enddo
        enddo
!
!       B(:,3(i-1)+k): the strain's derivative by node i's u_k
!
        do i=1,nope
          do k=1,3
            jj=3*(i-1)+k
            b(1,jj)=f(k,1)*shp(1,i)
            b(2,jj)=f(k,2)*shp(2,i)
            b(3,jj)=f(k,3)*shp(3,i)
            b(4,jj)=f(k,1)*shp(2,i)+f(k,2)*shp(1,i)
            b(5,jj)=f(k,1)*shp(3,i)+f(k,3)*shp(1,i)
            b(6,jj)=f(k,2)*shp(3,i)+f(k,3)*shp(2,i)
          enddo
        enddo
!
!       s(jj,ll): row jj the force, column ll the displacement
!
        wj=xsj*weight
        do ll=1,3*nope
          do j=1,6
            db(j,ll)=0.d0
            do m=1,6
              db(j,ll)=db(j,ll)+da(j,m)*b(m,ll)
            enddo
          enddo
        enddo
        do ll=1,3*nope
          do jj=1,3*nope
            do j=1,6
              s(jj,ll)=s(jj,ll)+b(j,jj)*db(j,ll)*wj
            enddo
          enddo
        enddo
      enddo
!
      return
      end
