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
!     A material named ABAQUSNL...: umat_abaqusnl.f turns the symmetric
!     part by U^-1 in each index before ccx assembles it, with or
!     without NLGEOM (U from the strain it hands the UMAT); D_a is
!     turned alike (sffcal_turn_by_inverse_stretch).
!
!     Elements: C3D8, C3D8I, C3D20 and C3D20R, at ccx's own points
!     (gauss.f) with its own shape functions; nope = their nodes. Other
!     elements and those with a local orientation keep the symmetric
!     tangent (said once on stdout): nope = 0, as for an element
!     without sffcal's material. A point the UMAT has not been called
!     at (none yet) adds nothing (said once). The "said" flags are SAVEd
!     and set from ccx's assembly threads: a race can only repeat a
!     message.
!
      subroutine sffcal_e_c3d_unsym(co,kon,ipkon,lakonl,nelem,vold,mi,
     &  iperturb,ielorien,norien,ielmat,matname,s,nope)
!
      implicit none
!
      logical corotated
!
      character*8 lakonl
      character*80 matname(*)
!
      integer kon(*),ipkon(*),nelem,mi(*),iperturb(*),
     &  ielorien(mi(3),*),norien,ielmat(mi(3),*),nope,indexe,mint3d,
     &  kk,i,j,k,m,jj,ll,found,iflag,said_type,said_orientation,
     &  said_point
!
      real*8 co(3,*),vold(0:mi(2),*),s(60,60),xl(3,23),shp(4,23),
     &  u(3,23),xsj,xi,et,ze,weight,da(6,6),f(3,3),b(6,60),db(6,60),wj,
     &  h(3,3),c(3,3)
!
      save said_type,said_orientation,said_point
      data said_type /0/
      data said_orientation /0/
      data said_point /0/
!
      include "gauss.f"
!
      nope=0
      call sffcal_umat_has_unsymmetric_part(nelem,found)
      if(found.eq.0) return
!
      if(lakonl(7:8).ne.'  ') then
        if(said_type.eq.0) then
          write(*,*) '*WARNING in sffcal_e_c3d_unsym: element ',
     &      nelem,' (',lakonl,') is expanded from a shell, beam or ',
     &      'plane element or layered: it keeps the symmetric part ',
     &      'of its user material''s tangent'
          said_type=1
        endif
        return
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
      corotated=matname(ielmat(1,nelem))(1:8).eq.'ABAQUSNL'
!
!     the displacements: for B under NLGEOM, for U under ABAQUSNL...
!
      indexe=ipkon(nelem)
      do i=1,nope
        do j=1,3
          xl(j,i)=co(j,kon(indexe+i))
          u(j,i)=vold(j,kon(indexe+i))
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
        if(found.eq.0) then
          if(said_point.eq.0) then
            write(*,*) '*WARNING in sffcal_e_c3d_unsym: element ',
     &        nelem,' point ',kk,' has no tangent from the UMAT yet:',
     &        ' it adds no unsymmetric part'
            said_point=1
          endif
          cycle
        endif
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
!       H = sum_i u_i (x) grad_0 N_i; F = I + H under NLGEOM, else I
!
        do k=1,3
          do m=1,3
            h(k,m)=0.d0
            do i=1,nope
              h(k,m)=h(k,m)+u(k,i)*shp(m,i)
            enddo
            f(k,m)=0.d0
            if(iperturb(2).eq.1) f(k,m)=h(k,m)
            if(k.eq.m) f(k,m)=f(k,m)+1.d0
          enddo
        enddo
!
!       C = I + 2 E of the strain the UMAT was handed: Green-Lagrange
!       under NLGEOM (F^T F), the small strain otherwise (I + H + H^T)
!
        if(corotated) then
          do k=1,3
            do m=1,3
              c(k,m)=h(k,m)+h(m,k)
              if(iperturb(2).eq.1) c(k,m)=c(k,m)+h(1,k)*h(1,m)+
     &          h(2,k)*h(2,m)+h(3,k)*h(3,m)
              if(k.eq.m) c(k,m)=c(k,m)+1.d0
            enddo
          enddo
          call sffcal_turn_by_inverse_stretch(c,da)
        endif
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
!
!     D_a turned as umat_abaqusnl.f turns the symmetric part: the tensor
!     A_ijkl = D_a(I(ij),J(kl)) (anisotropic.f's identification) turned
!     by T = U^-1 in each index, U the stretch of C = U^2 (given):
!     C = Z diag(w) Z^T, U^-1 = Z diag(w^-1/2) Z^T.
!
      subroutine sffcal_turn_by_inverse_stretch(cin,da)
!
      implicit none
!
      integer i,j,k,l,m,n,o,p,ier,matz,nn,iv(3,3),ir(6),ic(6)
!
      real*8 cin(3,3),da(6,6),c(3,3),w(3),z(3,3),fv1(3),fv2(3),t(3,3),
     &  a(3,3,3,3),sum
!
      data iv /1,4,5,4,2,6,5,6,3/
      data ir /1,2,3,1,1,2/
      data ic /1,2,3,2,3,3/
!
      do i=1,3
        do j=1,3
          c(i,j)=cin(i,j)
        enddo
      enddo
      nn=3
      matz=1
      call rs(nn,nn,c,w,matz,z,fv1,fv2,ier)
      if(ier.ne.0) then
        write(*,*) '*ERROR in sffcal_turn_by_inverse_stretch: ',
     &    'no eigenvalues of C'
        call exit(201)
      endif
      do i=1,3
        do j=1,3
          t(i,j)=0.d0
          do m=1,3
            t(i,j)=t(i,j)+z(i,m)*z(j,m)/dsqrt(w(m))
          enddo
        enddo
      enddo
      do i=1,3
        do j=1,3
          do k=1,3
            do l=1,3
              a(i,j,k,l)=da(iv(i,j),iv(k,l))
            enddo
          enddo
        enddo
      enddo
      do i=1,6
        do j=1,6
          sum=0.d0
          do m=1,3
            do n=1,3
              do o=1,3
                do p=1,3
                  sum=sum+a(m,n,o,p)*t(ir(i),m)*t(ic(i),n)*
     &              t(ir(j),o)*t(ic(j),p)
                enddo
              enddo
            enddo
          enddo
          da(i,j)=sum
        enddo
      enddo
!
      return
      end
